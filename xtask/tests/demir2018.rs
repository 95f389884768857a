//! The `demir2018` reproduction's worlds, and the target on the two
//! worlds Demir 2018's own implementation failed on (a concave obstacle and
//! two stacked obstacles): coverage of at least 99 %, every true critical
//! point found, no collision.

use oxcover::explore::explore_world;
use xtask::reproduce::demir2018;

#[test]
fn the_worlds_are_the_seeds_six_and_five_of_ours() {
    let worlds = demir2018::worlds().unwrap();
    assert_eq!(worlds.len(), 11);
    assert_eq!(
        worlds.iter().filter(|w| w.name.starts_with("fig")).count(),
        6
    );
    for w in &worlds {
        assert!(w.start.is_some(), "{} names a start", w.name);
        assert!(!w.critical_points(0.01).is_empty(), "{}", w.name);
    }
}

#[test]
fn concave_and_stacked_obstacles_are_covered_and_every_critical_point_found() {
    let worlds = demir2018::worlds().unwrap();
    for name in ["fig14_concave", "fig15_stacked"] {
        let w = worlds.iter().find(|w| w.name == name).unwrap();
        let o = explore_world(w, &demir2018::config(0.0, 0), None).unwrap();
        let m = &o.evaluation.metrics;
        assert!(m.coverage >= 0.99, "{name}: {}", m.coverage);
        assert_eq!(m.collisions, 0, "{name}");
        assert_eq!(o.exploration.collisions, 0, "{name}");
        assert!(o.found.iter().all(|&f| f), "{name}: {:?}", o.found);
        assert_eq!(o.spurious, 0, "{name}");
        assert!(o.exploration.complete, "{name}");
        // One loop of the graph per obstacle, as the free space's Reeb graph.
        let g = &o.exploration.graph;
        assert_eq!(
            g.edges.len() + 1 - g.nodes.len(),
            w.obstacles.len(),
            "{name}"
        );
    }
}
