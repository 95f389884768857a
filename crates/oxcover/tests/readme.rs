//! The README's library example, kept in step: the same lines run here, and
//! the test fails if the README no longer shows them.

#[test]
fn readme_library_example_runs_and_is_current() {
    use oxcover::{PlanRequest, parse_ascii, plan};
    let (map, _) = parse_ascii("......\n.##...\n......").unwrap();
    let outcome = plan(&map, &PlanRequest::new("dtc", map.resolution()).unwrap()).unwrap();
    assert_eq!(outcome.evaluation.metrics.coverage, 1.0);

    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md"))
        .expect("README");
    for line in [
        "use oxcover::{parse_ascii, plan, PlanRequest};",
        r#"let (map, _) = parse_ascii("......\n.##...\n......").unwrap();"#,
        r#"let outcome = plan(&map, &PlanRequest::new("dtc", map.resolution()).unwrap()).unwrap();"#,
        "assert_eq!(outcome.evaluation.metrics.coverage, 1.0);",
    ] {
        assert!(
            readme.contains(line),
            "README lost the example line `{line}`"
        );
    }
}
