//! `oxcover info` and `oxcover planners`: a map described, the planners listed.

use std::io::Write as _;
use std::path::PathBuf;

use oxcover::Result;
use oxcover::grid::components4;
use oxcover::pipeline::{metres, planners};
use oxcover::report::table;

use super::args::{MapArgs, load, map_rows};

#[derive(Debug, clap::Args)]
pub(crate) struct InfoArgs {
    /// Map file, or a rosbag2 bag (its topics are listed, then its map).
    pub(crate) map: PathBuf,
    #[command(flatten)]
    pub(crate) reading: MapArgs,
}

/// A bag's topics, with their types and message counts, as printed
/// lines; whether one is an OccupancyGrid (then the map is described
/// after them).
fn bag_topics(a: &InfoArgs) -> Result<(Vec<String>, bool)> {
    let mut bag = oxcover::rosbag::Bag::open(&a.map)?;
    let topics = bag.topics()?;
    let mut lines = vec![format!("{}: {} topics", a.map.display(), topics.len())];
    let w = topics
        .iter()
        .map(|t| t.name.len())
        .max()
        .unwrap_or(5)
        .max(5);
    let tw = topics
        .iter()
        .map(|t| t.type_name.len())
        .max()
        .unwrap_or(4)
        .max(4);
    lines.push(format!("  {:<w$}  {:<tw$}  messages", "topic", "type"));
    for t in &topics {
        lines.push(format!(
            "  {:<w$}  {:<tw$}  {:>8}",
            t.name, t.type_name, t.count
        ));
    }
    Ok((
        lines,
        a.reading.topic.is_some() || bag.map_topic(None).is_ok(),
    ))
}

pub(crate) fn cmd_info(a: &InfoArgs) -> Result<()> {
    // A bag's topics are printed once its map (if it has one) has been
    // read: a bag that fails prints its one error line and nothing else.
    let (topic_lines, has_map) = if oxcover::rosbag::is_bag(&a.map) {
        bag_topics(a)?
    } else {
        (Vec::new(), true)
    };
    if !has_map {
        let mut out = super::out::stdout();
        for l in &topic_lines {
            let _ = writeln!(out, "{l}");
        }
        return Ok(());
    }
    let map = load(&a.map, &a.reading)?;
    let f = map.frame();
    let (lo, hi) = f.bounds();
    let free = map.free_mask();
    let comps = components4(&free);
    let mut rows = map_rows(&map);
    rows.push(("origin".into(), format!("({}, {})", lo.x, lo.y)));
    rows.push((
        "extent".into(),
        format!("x {}..{}, y {}..{}", lo.x, hi.x, lo.y, hi.y),
    ));
    rows.push(("free components".into(), comps.count().to_string()));
    if let Some(l) = comps.largest() {
        rows.push((
            "largest component".into(),
            comps.sizes[l as usize - 1].to_string(),
        ));
    }
    if let Some(s) = free.true_cells().next() {
        let p = f.cell_center(s);
        rows.push((
            "default start".into(),
            format!("{},{}", metres(p.x), metres(p.y)),
        ));
    }
    let mut out = super::out::stdout();
    for l in &topic_lines {
        let _ = writeln!(out, "{l}");
    }
    let _ = writeln!(out, "{}", a.map.display());
    let _ = write!(out, "{}", table(&rows));
    Ok(())
}

pub(crate) fn cmd_planners() {
    let mut out = super::out::stdout();
    let list = planners();
    let w = list.iter().map(|p| p.name.len()).max().unwrap_or(4);
    let _ = writeln!(out, "{:<w$}  complete  description", "name");
    for p in &list {
        let _ = writeln!(
            out,
            "{:<w$}  {:<8}  {}",
            p.name,
            if p.complete { "yes" } else { "no" },
            p.summary
        );
    }
    let _ = writeln!(
        out,
        "\n{:<w$}  {:<8}  online sensor-based boustrophedon coverage of unknown polygonal worlds (Demir 2018): `oxcover explore WORLD.ron`",
        "sensor-bcd", "yes"
    );
}
