//! Sweeps are deterministic whatever the thread count, and shards merge into
//! the summary a single run gives.

use xtask::sweep::{
    Generator, Shard, SweepSpec, read_records, run, shard_file, summarise, to_lines,
};

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

/// The files of every shard of `spec` in `dir`, as `sweep --out` writes them.
fn shard_files(dir: &std::path::Path, s: &SweepSpec, count: usize) -> Vec<std::path::PathBuf> {
    (0..count)
        .map(|index| {
            let shard = Shard { index, count };
            let f = dir.join(format!("sweep-{index}.jsonl"));
            let text = shard_file(s, shard, &run(s, shard)).expect("lines");
            std::fs::write(&f, text).expect("write");
            f
        })
        .collect()
}

#[test]
fn merge_refuses_a_missing_repeated_or_truncated_shard_by_name() {
    let s = spec();
    let dir = std::env::temp_dir().join(format!("oxcover-merge-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let files = shard_files(&dir, &s, 4);
    let whole = summarise(&run(&s, Shard::default()));
    assert_eq!(summarise(&read_records(&files).expect("all shards")), whole);
    let err = |files: &[std::path::PathBuf]| {
        read_records(files)
            .map(|r| format!("merged {} maps", r.len()))
            .unwrap_or_else(|e| e.to_string())
    };
    // A killed array task: its file never appears.
    let e = err(&[files[0].clone(), files[1].clone(), files[3].clone()]);
    assert!(e.contains("shard 2/4 of the sweep is missing"), "{e}");
    let e = err(&files[..1]);
    assert!(
        e.contains("shards 1/4, 2/4, 3/4 of the sweep are missing"),
        "{e}"
    );
    // The same shard given twice.
    let e = err(&[
        files[0].clone(),
        files[1].clone(),
        files[1].clone(),
        files[2].clone(),
    ]);
    assert!(e.contains("shard 1/4 appears twice"), "{e}");
    // A shard cut short (its last line lost).
    let text = std::fs::read_to_string(&files[3]).expect("read");
    let cut: Vec<&str> = text.lines().collect();
    std::fs::write(&files[3], cut[..cut.len() - 1].join("\n")).expect("write");
    let e = err(&files);
    assert!(e.contains("shard 3/4 holds 5 of its 6 maps"), "{e}");
    // A file of records without a header (not a shard file).
    std::fs::write(
        &files[3],
        to_lines(&run(&s, Shard { index: 3, count: 4 })).expect("lines"),
    )
    .expect("write");
    let e = err(&files);
    assert!(
        e.contains("sweep-3.jsonl: line 1: not a shard header"),
        "{e}"
    );
    // A shard of another sweep.
    let other = SweepSpec { seed: 7, ..spec() };
    let text = shard_file(
        &other,
        Shard { index: 3, count: 4 },
        &run(&other, Shard { index: 3, count: 4 }),
    )
    .expect("lines");
    std::fs::write(&files[3], text).expect("write");
    let e = err(&files);
    assert!(e.contains("are shards of different sweeps"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
