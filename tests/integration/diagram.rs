//! `impact diagram` through the binary.

use crate::support::*;

#[test]
fn diagram_writes_svg_png_and_a_page() {
    let dir = scratch("diagram");
    for ext in ["svg", "png"] {
        let out = dir.join(format!("d.{ext}"));
        let o = impact_words(
            "diagram --x 0.4 --alpha 0.05 --out",
            &[out.to_str().unwrap()],
        );
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(out.metadata().unwrap().len() > 10_000);
    }
    let svg = std::fs::read_to_string(dir.join("d.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("takeoff-path") && svg.contains("<text"));
    assert_eq!(&std::fs::read(dir.join("d.png")).unwrap()[1..4], b"PNG");
    let out = dir.join("d2.svg");
    let o = impact_words(
        "diagram --x 0.4 --alpha 0.05 --out",
        &[out.to_str().unwrap(), "--html"],
    );
    assert!(o.status.success());
    let page = std::fs::read_to_string(dir.join("d2.html")).unwrap();
    assert!(
        page.contains("<title>front") && page.contains("final takeoff") && page.contains("<table>")
    );
    let bare = dir.join("d3.svg");
    let o = impact_words(
        "diagram --x 0.4 --alpha 0.05 --out",
        &[bare.to_str().unwrap(), "--no-fronts"],
    );
    assert!(o.status.success());
    assert!(
        !std::fs::read_to_string(&bare)
            .unwrap()
            .contains("class=\"front\""),
        "--no-fronts"
    );
}

#[test]
fn chain_and_side_by_side_diagrams() {
    let dir = scratch("diagram-chain");
    for extra in [vec!["--engine", "chain"], vec!["--side-by-side"]] {
        let out = dir.join("c.svg");
        let mut args = vec![
            "diagram",
            "--x",
            "0.3",
            "--alpha",
            "0.3",
            "--n",
            "300",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(extra.iter().copied());
        let o = impact(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(
            std::fs::read_to_string(&out)
                .unwrap()
                .contains("data:image/png;base64,")
        );
    }
    // a viscous scene can only be drawn from the chain
    let o = impact_words(
        "diagram data/scenes/viscous-bilayer.json --out",
        &[dir.join("v.svg").to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--engine chain"));
}

/// A steel base under gel (in reduced units, so the steel's transit is
/// `1.2e-4` of the gel's) rebounds alone after `2 t1`: the default window
/// `[0, 1.12 t_c]` is a ten-thousandth of the `3 sum t_i` the chain's
/// frames were spread over, and held none. The chain alone and beside the
/// exact picture now sample that window with over a hundred frames.
#[test]
fn a_contact_far_shorter_than_the_transits_is_drawn() {
    let dir = scratch("diagram-short-contact");
    let scene = steel_under_gel(&dir, None);
    for extra in [["--engine", "chain"], ["--side-by-side", "--no-fronts"]] {
        let out = dir.join("d.svg");
        let mut args = vec!["diagram", scene.to_str().unwrap(), "--n", "400"];
        args.extend(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        let o = impact(&args);
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
        let svg = std::fs::read_to_string(&out).unwrap();
        assert!(!svg.contains("no chain frames"), "{extra:?}");
        let frames: usize = svg
            .split("chain field: ")
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .and_then(|n| n.parse().ok())
            .expect("the chain's frame count");
        assert!(frames > 100, "{extra:?}: {frames} frames in the window");
    }
}

#[test]
fn bad_diagram_input() {
    let dir = scratch("diagram-bad");
    for (args, needle) in [
        (
            vec!["--out", "x.pdf"],
            "--out must end in .svg, .png or .html",
        ),
        (
            vec!["--out", "x.svg", "--t-end", "-1"],
            "--t-end must be a finite number > 0",
        ),
        (
            vec!["--out", "x.svg", "--t-start", "3", "--t-end", "2"],
            "--t-start must be before --t-end",
        ),
        (
            vec!["--out", "x.svg", "--strain-scale", "0"],
            "--strain-scale",
        ),
    ] {
        let mut all = vec!["diagram", "--x", "0.4", "--alpha", "0.05"];
        let out = dir.join(args[1]);
        let mut args = args.clone();
        let out_s = out.to_string_lossy().into_owned();
        args[1] = &out_s;
        all.extend(args);
        let o = impact(&all);
        assert_eq!(o.status.code(), Some(2), "{all:?}");
        assert!(stderr(&o).contains(needle), "{all:?}: {}", stderr(&o));
    }
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));
}

/// Where fronts multiply without bound the diagram, which draws every
/// front, stops at its event cap at once (exit 1, naming the way out)
/// instead of recording fronts until memory runs out; nothing is written.
#[test]
fn a_scene_whose_fronts_multiply_is_refused_quickly() {
    let dir = scratch("diagram-multiply");
    let out = dir.join("d.svg");
    let o = impact(&[
        "diagram",
        "data/scenes/steel-under-rubber.json",
        "--out",
        &out.to_string_lossy(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("fronts multiply beyond 1000000 events"),
        "{}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("--engine chain"));
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));
}
