use oxcover_grid::{Coverability, DiscRobot, Point};
use oxcover_grid::footprint::covered_cells;
use oxcover_planners::sensor_bcd::{explore, Config};
use oxcover_robot::{World, WorldGeometry};

fn run(text: &str, start: (f64, f64)) {
    let world = World::parse(text, "t").unwrap();
    let g = WorldGeometry::new(&world);
    let cfg = Config::default();
    let t0 = std::time::Instant::now();
    let ex = explore(&g, start, &cfg);
    let ex = match ex { Ok(e) => e, Err(e) => { println!("ERR {e}"); return; } };
    let map = world.rasterise();
    let cov = Coverability::new(&map, DiscRobot::new(cfg.robot_radius, cfg.tool_radius).unwrap(), Some(Point::new(start.0, start.1))).unwrap();
    let pts: Vec<Point> = ex.trace.iter().map(|t| Point::new(t.x, t.y)).collect();
    let covered = covered_cells(map.frame(), &pts, cfg.tool_radius);
    let n = cov.coverable.count_true();
    let c = cov.coverable.cells().filter(|&c| cov.coverable[c] && covered[c]).count();
    println!("{:?} len {:.1} cov {:.4} coll {} minclr {:.3} nodes {} edges {} {:?} {:?}", t0.elapsed(), ex.length_m, c as f64 / n as f64, ex.collisions, ex.min_clearance, ex.graph.nodes.len(), ex.graph.edges.len(), ex.counters, ex.complete);
    for nd in &ex.graph.nodes { println!("  node {:?} {:?} {}", nd.at, nd.kind.label(), nd.confirmed); }
    let truth = world.critical_points();
    for t in &truth { let d = ex.graph.nodes.iter().map(|n| t.distance(n.at)).fold(f64::INFINITY, f64::min); println!("  true {:?} {} nearest {:.3}", t.at, t.kind.label(), d); }
}

#[test]
fn scratch() {
    run("(name: \"t\", width: 4.0, height: 3.0, resolution: 0.025, obstacles: [])", (0.5, 0.5));
    run("(name: \"t\", width: 10.0, height: 10.0, resolution: 0.025, obstacles: [Polygon([(3.0, 5.0), (5.0, 3.0), (7.0, 5.5), (4.5, 7.0)])])", (0.5, 9.0));
}
