use oxcover_grid::footprint::covered_cells;
use oxcover_grid::{Coverability, DiscRobot, Point};
use oxcover_planners::sensor_bcd::{Config, explore};
use oxcover_robot::{RandomWorldSpec, World, WorldGeometry, random_world};

fn run(text: &str, start: (f64, f64)) {
    let world = World::parse(text, "t").unwrap();
    runw(&world, start, false);
}

fn runw(world: &World, start: (f64, f64), quiet: bool) {
    let g = WorldGeometry::new(&world);
    let cfg = Config {
        noise_sd: std::env::var("NOISE")
            .map(|v| v.parse().unwrap())
            .unwrap_or(0.0),
        ..Config::default()
    };
    let t0 = std::time::Instant::now();
    let ex = explore(&g, start, &cfg);
    let ex = match ex {
        Ok(e) => e,
        Err(e) => {
            println!("ERR {e}");
            return;
        }
    };
    let map = world.rasterise();
    let cov = Coverability::new(
        &map,
        DiscRobot::new(cfg.robot_radius, cfg.tool_radius).unwrap(),
        Some(Point::new(start.0, start.1)),
    )
    .unwrap();
    let pts: Vec<Point> = ex.trace.iter().map(|t| Point::new(t.x, t.y)).collect();
    let covered = covered_cells(map.frame(), &pts, cfg.tool_radius);
    let n = cov.coverable.count_true();
    let c = cov
        .coverable
        .cells()
        .filter(|&c| cov.coverable[c] && covered[c])
        .count();
    println!(
        "{:?} len {:.1} cov {:.4} coll {} minclr {:.3} nodes {} edges {} {:?} {:?}",
        t0.elapsed(),
        ex.length_m,
        c as f64 / n as f64,
        ex.collisions,
        ex.min_clearance,
        ex.graph.nodes.len(),
        ex.graph.edges.len(),
        ex.counters,
        ex.complete
    );
    if quiet {
        let truth = world.critical_points(cfg.x_hysteresis());
        let missed = truth
            .iter()
            .filter(|t| ex.graph.nodes.iter().all(|n| t.distance(n.at) > 0.25))
            .count();
        let spur = ex
            .graph
            .nodes
            .iter()
            .filter(|n| truth.iter().all(|t| t.distance(n.at) > 0.25))
            .count();
        println!(
            "  truth {} missed {} spurious {}",
            truth.len(),
            missed,
            spur
        );
        for t in truth
            .iter()
            .filter(|t| ex.graph.nodes.iter().all(|n| t.distance(n.at) > 0.25))
        {
            let (d, n) = ex
                .graph
                .nodes
                .iter()
                .map(|n| (t.distance(n.at), n))
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .unwrap();
            println!(
                "    missed {:?} {} nearest {:.3} {:?} {} clr {:.3}",
                t.at,
                t.kind.label(),
                d,
                n.at,
                n.kind.label(),
                WorldGeometry::new(world).clearance(t.at).0
            );
        }
        return;
    }
    for nd in &ex.graph.nodes {
        println!("  node {:?} {:?} {}", nd.at, nd.kind.label(), nd.confirmed);
    }
    let truth = world.critical_points(cfg.x_hysteresis());
    for t in &truth {
        let d = ex
            .graph
            .nodes
            .iter()
            .map(|n| t.distance(n.at))
            .fold(f64::INFINITY, f64::min);
        println!("  true {:?} {} nearest {:.3}", t.at, t.kind.label(), d);
    }
}

#[test]
fn random() {
    for seed in 0..12 {
        let w = random_world(seed, &RandomWorldSpec::default());
        print!("seed {seed} obs {} ", w.obstacles.len());
        runw(&w, w.start.unwrap(), true);
    }
}

#[test]
fn scratch() {
    run(
        "(name: \"t\", width: 4.0, height: 3.0, resolution: 0.025, obstacles: [])",
        (0.5, 0.5),
    );
    run(
        "(name: \"t\", width: 10.0, height: 10.0, resolution: 0.025, obstacles: [Polygon([(3.0, 5.0), (5.0, 3.0), (7.0, 5.5), (4.5, 7.0)])])",
        (0.5, 9.0),
    );
}

fn svg(world: &World, ex: &oxcover_planners::sensor_bcd::Exploration, path: &str) {
    let s = 100.0;
    let h = world.height;
    let mut o = format!(
        "<svg xmlns='http://www.w3.org/2000/svg' width='{}' height='{}'>",
        world.width * s,
        h * s
    );
    for sh in &world.obstacles {
        if let oxcover_robot::Shape::Polygon(v) = sh {
            let pts: Vec<String> = v
                .iter()
                .map(|p| format!("{},{}", p.0 * s, (h - p.1) * s))
                .collect();
            o += &format!("<polygon points='{}' fill='#444'/>", pts.join(" "));
        }
    }
    let cols = ["black", "red", "blue", "green", "orange"];
    for w in ex.trace.windows(2) {
        o += &format!(
            "<line x1='{}' y1='{}' x2='{}' y2='{}' stroke='{}' stroke-width='1'/>",
            w[0].x * s,
            (h - w[0].y) * s,
            w[1].x * s,
            (h - w[1].y) * s,
            cols[w[1].state.code() as usize]
        );
    }
    for n in &ex.graph.nodes {
        o += &format!(
            "<circle cx='{}' cy='{}' r='5' fill='magenta'/>",
            n.at.0 * s,
            (h - n.at.1) * s
        );
    }
    for t in world.critical_points(0.003) {
        o += &format!(
            "<circle cx='{}' cy='{}' r='8' fill='none' stroke='purple'/>",
            t.at.0 * s,
            (h - t.at.1) * s
        );
    }
    o += "</svg>";
    std::fs::write(path, o).unwrap();
}

#[test]
fn one() {
    let seed: u64 = std::env::var("SEED").unwrap_or("9".into()).parse().unwrap();
    let w = match std::env::var("WORLD") {
        Ok(f) => World::read(std::path::Path::new(&f)).unwrap(),
        Err(_) => random_world(seed, &RandomWorldSpec::default()),
    };
    let g = WorldGeometry::new(&w);
    let cfg = Config {
        noise_sd: std::env::var("NOISE")
            .map(|v| v.parse().unwrap())
            .unwrap_or(0.0),
        ..Config::default()
    };
    let ex = explore(&g, w.start.unwrap(), &cfg).unwrap();
    svg(&w, &ex, "/tmp/one.svg");
    for sh in &w.obstacles {
        println!("{sh:?}");
    }
    for t in w.critical_points(0.003) {
        println!("TRUE {:?} {:?} {}", t.at, t.to, t.kind.label());
    }
    for n in &ex.graph.nodes {
        println!(
            "NODE {:?} robot {:?} span {:?} {}",
            n.at,
            n.robot,
            n.span,
            n.kind.label()
        );
    }
}

#[test]
fn demir() {
    let dir = "/work/main/fixtures/worlds/demir2018";
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    for f in files {
        let w = World::read(&f).unwrap();
        print!("{:22} ", w.name);
        runw(&w, w.start.unwrap(), true);
    }
}
