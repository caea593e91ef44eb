//! `vsrlab run` writes each run's best replay; `vsrlab view` lists a results folder's runs,
//! simulates a best robot without a replay on demand (the same episode), serves on loopback and
//! stops on Ctrl-C. The page itself is tested in a browser by web-test/run.sh.

use crate::common;
use common::{ok, vsrlab};
use std::io::{Read, Write};
use std::net::TcpStream;

const EXPERIMENT: &str = r#"
runs = 2
seed = 3

[representation]
body = "biped-4x3"
sensors = "uniform-vxy+a+t-0"
brain = { kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }

[task]
duration = 4.0

[optimizer]
kind = "ga"
population_size = 6
offspring_size = 6

[stop]
generations = 2
"#;

/// `GET path` on the viewer: status line and body.
fn get(address: &str, path: &str) -> (String, String) {
    let mut s = TcpStream::connect(address).unwrap();
    write!(s, "GET {path} HTTP/1.1\r\nHost: {address}\r\n\r\n").unwrap();
    let mut text = String::new();
    s.read_to_string(&mut text).unwrap();
    let (head, body) = text.split_once("\r\n\r\n").unwrap();
    (head.lines().next().unwrap().to_string(), body.to_string())
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap()
}

#[test]
fn runs_write_best_replays_and_view_serves_a_results_folder_until_ctrl_c() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("exp.toml");
    std::fs::write(&file, EXPERIMENT).unwrap();
    let out = dir.path().join("out");
    let (success, text) = vsrlab(&["run", file.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(success, "{text}");
    let written = json(&std::fs::read_to_string(out.join("run-01/best.replay.json")).unwrap());
    assert_eq!(written["format"], "vsrlab-replay");
    assert_eq!(
        written["frames"], 121,
        "4 s (241 steps, as the original counts) at 30 frames per second"
    );
    assert!(written["title"].as_str().unwrap().contains("run 1"));
    // Without its replay, the best robot is simulated when the page asks for it.
    std::fs::remove_file(out.join("run-01/best.replay.json")).unwrap();

    let viewer = common::start_viewer(&["view", out.to_str().unwrap(), "--port", "0"], dir.path());
    let address = viewer.address();
    assert!(address.starts_with("127.0.0.1:"), "{}", viewer.first_line);
    assert!(viewer.first_line.contains("2 replays"), "{}", viewer.first_line);

    let list = json(&get(&address, "/api/replays").1);
    assert_eq!(list[0]["name"], "run-00");
    assert_eq!(list[0]["shown"], true);
    assert_eq!(list[1]["name"], "run-01");
    assert_eq!(list[1]["shown"], false);
    let made = json(&get(&address, list[1]["url"].as_str().unwrap()).1);
    assert_eq!(
        made["channels"], written["channels"],
        "the same episode as the run's own replay"
    );
    let (status, page) = get(&address, "/");
    assert!(status.contains("200") && page.contains("viewer.js"), "{status}");
    assert!(get(&address, "/../exp.toml").0.contains("404"));

    // The live monitor: both runs finished, with a curve point per generation.
    let monitor = json(&get(&address, "/api/monitor").1);
    let runs = monitor["experiments"][0]["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    for run in runs {
        assert_eq!(run["state"], "finished", "{run}");
        assert_eq!(run["curve"].as_array().unwrap().len(), 2, "two generations: {run}");
        assert_eq!(run["best_stamp"], "final");
    }
    assert!(monitor["experiments"][0]["eta"].is_null(), "nothing left");
    let (stopped, rest) = viewer.interrupt();
    assert!(stopped, "{rest}");
    assert!(rest.contains("viewer stopped"), "{rest}");

    // A run caught in progress (no summary yet): running, with an ETA, and its best so far made
    // from its latest snapshot.
    std::fs::remove_file(out.join("run-01/summary.json")).unwrap();
    std::fs::remove_file(out.join("run-01/best.robot.json")).unwrap();
    let viewer = common::start_viewer(&["view", out.to_str().unwrap(), "--port", "0"], dir.path());
    let address = viewer.address();
    let monitor = json(&get(&address, "/api/monitor").1);
    let run = &monitor["experiments"][0]["runs"][1];
    assert_eq!(run["state"], "running", "{run}");
    assert_eq!(run["best_stamp"], 12, "the snapshot after 12 evaluations: {run}");
    assert!(run["eta"].is_number(), "{run}");
    let (status, body) = get(&address, "/live/0/1");
    assert!(status.contains("200"), "{status}: {body}");
    let replay = json(&body);
    assert!(
        replay["title"]
            .as_str()
            .unwrap()
            .contains("best so far (after 12 evaluations"),
        "{}",
        replay["title"]
    );
    assert!(get(&address, "/live/0/2").0.contains("404"));
    assert!(viewer.interrupt().0);
}

#[test]
fn view_names_what_is_wrong_with_its_arguments() {
    let dir = tempfile::tempdir().unwrap();
    let (success, text) = vsrlab(&["view", dir.path().join("nothing.replay.json").to_str().unwrap()]);
    assert!(!success);
    assert!(text.contains("no such file or folder"), "{text}");
    let (success, text) = vsrlab(&["view", dir.path().to_str().unwrap()]);
    assert!(!success);
    assert!(text.contains("no replay files"), "{text}");
    let robot = dir.path().join("bad.robot.json");
    std::fs::write(&robot, "{\"format\": 1}").unwrap();
    let (success, text) = vsrlab(&["view", robot.to_str().unwrap()]);
    assert!(!success);
    assert!(text.contains("bad.robot.json"), "{text}");
    let busy = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = busy.local_addr().unwrap().port().to_string();
    let replay = dir.path().join("a.replay.json");
    ok(&["simulate", "--duration", "1", "--replay", replay.to_str().unwrap()]);
    let (success, text) = vsrlab(&["view", replay.to_str().unwrap(), "--port", &port]);
    assert!(!success);
    assert!(text.contains("--port") && text.contains("in use"), "{text}");
}
