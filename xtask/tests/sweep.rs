//! Sweeps are deterministic whatever the thread count, and shards merge into
//! the summary a single run gives.

use xtask::sweep::{Generator, Shard, SweepSpec, run, summarise, to_lines};

fn spec() -> SweepSpec {
    SweepSpec {
        planners: vec!["dtc".into(), "grid-cover".into(), "rect-priority".into()],
        size: 12,
        density: 0.2,
        count: 24,
        seed: 42,
        generator: Generator::Connected,
        timing: false,
    }
}

fn with_threads<T: Send>(n: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .expect("thread pool")
        .install(f)
}

#[test]
fn same_output_with_one_or_many_threads() {
    let s = spec();
    let one = with_threads(1, || to_lines(&run(&s, Shard::default())).expect("lines"));
    let four = with_threads(4, || to_lines(&run(&s, Shard::default())).expect("lines"));
    assert_eq!(one, four);
    assert_eq!(one.lines().count(), 24);
}

#[test]
fn shards_merge_into_the_single_run_summary() {
    let s = spec();
    let whole = summarise(&run(&s, Shard::default()));
    let mut parts = Vec::new();
    for index in [2, 0, 1] {
        parts.extend(run(&s, Shard { index, count: 3 }));
    }
    assert_eq!(summarise(&parts), whole);
    assert_eq!(whole.maps, 24);
    let dtc = &whole.planners["dtc"];
    assert_eq!((dtc.runs, dtc.errors), (24, 0));
    assert_eq!(dtc.coverage_min, 1.0);
    assert!(
        "1/3".parse::<Shard>().is_ok()
            && "3/3".parse::<Shard>().is_err()
            && "x".parse::<Shard>().is_err()
    );
}
