//! The replay viewer's web server: serves the page (shipped in the binary) and a fixed list of
//! replays on the loopback interface (docs/viewer.md).
//!
//! Only the page's three files and `/replay/<index>` of the listed replays are served: no URL is
//! ever turned into a file-system path, so nothing outside them can be read. One thread per
//! connection, one request per connection; replays are produced on first request (read from a
//! file, or simulated) and kept. A viewer of experiments in progress also has a [`LiveSource`]:
//! `/api/monitor` (their state now) and `/live/<experiment>/<run>` (a run's best so far), asked
//! afresh on every request.

use std::collections::HashMap;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{Ipv4Addr, SocketAddr, TcpListener, TcpStream};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use vsrlab_tasks::files::read_bytes;

/// The page.
pub const INDEX_HTML: &str = include_str!("../web/index.html");
/// The page's script.
pub const VIEWER_JS: &str = include_str!("../web/viewer.js");
/// The page's style sheet.
pub const VIEWER_CSS: &str = include_str!("../web/viewer.css");

/// Longest request head read (bytes).
const MAX_REQUEST: u64 = 16 * 1024;

/// Why a replay maker failed: its own error (an episode that blew up, a trace that cannot be
/// encoded), shown to the page as text.
pub type MakeError = Box<dyn std::error::Error + Send + Sync>;

/// Makes a replay's JSON text on demand (e.g. by simulating a robot file).
pub type ReplayMaker = Box<dyn Fn() -> Result<Vec<u8>, MakeError> + Send + Sync>;

/// A replay's bytes, or why it could not be made; made once and shared by every request.
type Made = Result<Arc<Vec<u8>>, Arc<dyn std::error::Error + Send + Sync>>;

/// Where a listed replay comes from.
pub enum ReplaySource {
    /// A replay file, read when first asked for.
    File(PathBuf),
    /// Made when first asked for.
    Make(ReplayMaker),
}

/// One replay the viewer lists.
pub struct ViewerEntry {
    /// Name shown in the list.
    pub name: String,
    /// Where the replay comes from.
    pub source: ReplaySource,
    /// Whether the page shows it when it opens.
    pub shown: bool,
}

/// Experiments watched while they run (`vsrlab view OUT` on a run's output folder).
pub trait LiveSource: Send + Sync {
    /// Their state now, as the JSON the page's monitor reads (docs/viewer.md).
    fn status(&self) -> Result<Vec<u8>, MakeError>;
    /// A replay of the best robot so far of run `run` of experiment `experiment`; `None` when
    /// there is no such run or it has no best yet.
    fn best_replay(&self, experiment: usize, run: usize) -> Option<Result<Vec<u8>, MakeError>>;
}

/// The served page and replays.
pub struct Viewer {
    entries: Vec<ViewerEntry>,
    cache: Mutex<HashMap<usize, Made>>,
    labelling: Option<Vec<u8>>,
    live: Option<Box<dyn LiveSource>>,
}

/// An HTTP response: status, content type, body.
struct Response {
    status: &'static str,
    content_type: &'static str,
    body: Arc<Vec<u8>>,
}

impl Response {
    fn ok(content_type: &'static str, body: Vec<u8>) -> Response {
        Response {
            status: "200 OK",
            content_type,
            body: Arc::new(body),
        }
    }
    fn text(status: &'static str, message: String) -> Response {
        Response {
            status,
            content_type: "text/plain; charset=utf-8",
            body: Arc::new(message.into_bytes()),
        }
    }
}

impl Viewer {
    /// A viewer of these replays.
    pub fn new(entries: Vec<ViewerEntry>) -> Viewer {
        Viewer {
            entries,
            cache: Mutex::new(HashMap::new()),
            labelling: None,
            live: None,
        }
    }

    /// The same viewer, also monitoring experiments in progress ([`LiveSource`]).
    pub fn with_live(mut self, live: Box<dyn LiveSource>) -> Viewer {
        self.live = Some(live);
        self
    }

    /// The same viewer, also serving a `vsrlab label` folder's `labelling.json` (robots and
    /// classes) at `/api/labelling`, so that the page offers the labelling choices beside each
    /// replay whose name is a robot's id.
    pub fn with_labelling(mut self, labelling: Vec<u8>) -> Viewer {
        self.labelling = Some(labelling);
        self
    }

    /// The list the page reads: `[{"name", "url", "shown"}]`.
    fn listing(&self) -> Vec<u8> {
        let list: Vec<serde_json::Value> = self
            .entries
            .iter()
            .enumerate()
            .map(|(i, e)| serde_json::json!({"name": e.name, "url": format!("/replay/{i}"), "shown": e.shown}))
            .collect();
        serde_json::to_vec(&list).expect("listings serialise")
    }

    /// Replay `index`'s bytes, made once.
    fn replay(&self, index: usize) -> Option<Made> {
        let entry = self.entries.get(index)?;
        if let Some(done) = self.cache.lock().ok()?.get(&index) {
            return Some(done.clone());
        }
        let made: Made = match &entry.source {
            ReplaySource::File(path) => read_bytes(path).map_err(|e| Arc::new(e) as _),
            ReplaySource::Make(make) => made_safely(make),
        }
        .map(Arc::new);
        self.cache.lock().ok()?.insert(index, made.clone());
        Some(made)
    }

    /// The response to `GET path`.
    fn respond(&self, path: &str) -> Response {
        let path = path.split(['?', '#']).next().unwrap_or("");
        match path {
            "/" | "/index.html" => Response::ok("text/html; charset=utf-8", INDEX_HTML.as_bytes().to_vec()),
            "/viewer.js" => Response::ok("text/javascript; charset=utf-8", VIEWER_JS.as_bytes().to_vec()),
            "/viewer.css" => Response::ok("text/css; charset=utf-8", VIEWER_CSS.as_bytes().to_vec()),
            "/api/replays" => Response::ok("application/json", self.listing()),
            "/api/labelling" => match &self.labelling {
                Some(bytes) => Response::ok("application/json", bytes.clone()),
                None => Response::text("404 Not Found", "not a labelling folder".to_string()),
            },
            "/api/monitor" => match &self.live {
                Some(live) => match guarded(|| live.status()) {
                    Ok(bytes) => Response::ok("application/json", bytes),
                    Err(e) => Response::text("500 Internal Server Error", e.to_string()),
                },
                None => Response::text("404 Not Found", "no experiment in progress is watched".to_string()),
            },
            _ if path.starts_with("/live/") => self.live_best(path),
            _ => match path.strip_prefix("/replay/").and_then(|i| i.parse::<usize>().ok()) {
                Some(i) => match self.replay(i) {
                    Some(Ok(bytes)) => Response {
                        status: "200 OK",
                        content_type: "application/json",
                        body: bytes,
                    },
                    Some(Err(e)) => Response::text("500 Internal Server Error", e.to_string()),
                    None => Response::text("404 Not Found", format!("no replay {i}")),
                },
                None => Response::text(
                    "404 Not Found",
                    "not found: this server only serves the viewer and its listed replays".to_string(),
                ),
            },
        }
    }

    /// `/live/<experiment>/<run>`: that run's best so far.
    fn live_best(&self, path: &str) -> Response {
        let mut parts = path["/live/".len()..].split('/').map(|p| p.parse::<usize>().ok());
        let (Some(live), Some(experiment), Some(run), None) =
            (&self.live, parts.next().flatten(), parts.next().flatten(), parts.next())
        else {
            return Response::text("404 Not Found", "not a run being watched".to_string());
        };
        let mut missing = false;
        let made = guarded(|| {
            live.best_replay(experiment, run).unwrap_or_else(|| {
                missing = true;
                Err(format!("run {run} of experiment {experiment} has no best robot yet").into())
            })
        });
        match made {
            Ok(bytes) => Response::ok("application/json", bytes),
            Err(e) if missing => Response::text("404 Not Found", e.to_string()),
            Err(e) => Response::text("500 Internal Server Error", e.to_string()),
        }
    }

    /// Answers one request on `stream`.
    fn handle(&self, stream: TcpStream) -> std::io::Result<()> {
        stream.set_read_timeout(Some(Duration::from_secs(10)))?;
        let mut reader = BufReader::new(stream.try_clone()?.take(MAX_REQUEST));
        // lines as bytes: a request that is not UTF-8 gets an answer too (405 or 404)
        let line = |reader: &mut BufReader<_>| -> std::io::Result<String> {
            let mut bytes = Vec::new();
            reader.read_until(b'\n', &mut bytes)?;
            Ok(String::from_utf8_lossy(&bytes).into_owned())
        };
        let request_line = line(&mut reader)?;
        let mut foreign_host = None;
        loop {
            let header = line(&mut reader)?;
            if header.is_empty() || header == "\r\n" || header == "\n" {
                break;
            }
            if let Some((name, value)) = header.split_once(':') {
                if name.trim().eq_ignore_ascii_case("host") && !is_loopback_host(value) {
                    foreign_host = Some(value.trim().to_string());
                }
            }
        }
        let mut parts = request_line.split_whitespace();
        let (method, target) = (parts.next().unwrap_or(""), parts.next().unwrap_or(""));
        let response = match (method, foreign_host) {
            (_, Some(host)) => Response::text(
                "403 Forbidden",
                format!(
                    "host {host:?} is not this machine's loopback: the viewer answers only localhost and 127.0.0.1"
                ),
            ),
            ("GET" | "HEAD", None) => self.respond(target),
            _ => Response::text("405 Method Not Allowed", "only GET and HEAD".to_string()),
        };
        let mut out = stream;
        write!(
            out,
            "HTTP/1.1 {}\r\nContent-Type: {}\r\nContent-Length: {}\r\nCache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nConnection: close\r\n\r\n",
            response.status,
            response.content_type,
            response.body.len()
        )?;
        if method != "HEAD" {
            out.write_all(&response.body)?;
        }
        out.flush()
    }
}

/// Runs a replay maker, turning a panic inside it (a simulation that breaks an invariant) into
/// an error the page shows, so that one bad robot never takes the server down.
fn made_safely(make: &ReplayMaker) -> Result<Vec<u8>, Arc<dyn std::error::Error + Send + Sync>> {
    guarded(make).map_err(Arc::from)
}

/// Runs `make`, turning a panic inside it into an error.
fn guarded(make: impl FnOnce() -> Result<Vec<u8>, MakeError>) -> Result<Vec<u8>, MakeError> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(make)) {
        Ok(made) => made,
        Err(panic) => {
            let what = panic
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("no message");
            Err(MakeError::from(format!(
                "making this replay failed inside vsrlab ({what}); please report it"
            )))
        }
    }
}

/// Whether a request's `Host` header names this machine's loopback interface (`localhost`,
/// `127.x.x.x`, `[::1]`, with or without a port). A page from elsewhere that rebinds its own
/// host name to 127.0.0.1 (DNS rebinding) sends its own name, and is refused.
fn is_loopback_host(host: &str) -> bool {
    let host = host.trim();
    let name = if let Some(rest) = host.strip_prefix('[') {
        rest.split(']').next().unwrap_or("")
    } else {
        host.rsplit_once(':').map_or(host, |(name, port)| {
            if port.chars().all(|c| c.is_ascii_digit()) {
                name
            } else {
                host
            }
        })
    };
    let name = name.trim_end_matches('.').to_ascii_lowercase();
    name == "localhost"
        || name.ends_with(".localhost")
        || name.parse::<std::net::IpAddr>().is_ok_and(|ip| ip.is_loopback())
}

/// Binds the viewer's port on 127.0.0.1 (0: any free port).
pub fn bind(port: u16) -> std::io::Result<TcpListener> {
    TcpListener::bind(SocketAddr::from((Ipv4Addr::LOCALHOST, port)))
}

/// Serves `viewer` on `listener` until `stop` is set (checked every 5 ms while idle).
pub fn serve(listener: TcpListener, viewer: Arc<Viewer>, stop: &AtomicBool) -> std::io::Result<()> {
    listener.set_nonblocking(true)?;
    while !stop.load(Ordering::SeqCst) {
        match listener.accept() {
            Ok((stream, _)) => {
                stream.set_nonblocking(false)?;
                let viewer = viewer.clone();
                std::thread::spawn(move || {
                    let _ = viewer.handle(stream);
                });
            }
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => std::thread::sleep(Duration::from_millis(5)),
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn get(addr: SocketAddr, target: &str) -> (String, String) {
        get_from(addr, target, "localhost:8765")
    }

    fn get_from(addr: SocketAddr, target: &str, host: &str) -> (String, String) {
        let mut s = TcpStream::connect(addr).unwrap();
        write!(s, "GET {target} HTTP/1.1\r\nHost: {host}\r\n\r\n").unwrap();
        let mut text = String::new();
        s.read_to_string(&mut text).unwrap();
        let (head, body) = text.split_once("\r\n\r\n").unwrap();
        (head.lines().next().unwrap().to_string(), body.to_string())
    }

    /// Serves `entries` on a free port until the returned flag is set.
    fn start(
        entries: Vec<ViewerEntry>,
    ) -> (
        SocketAddr,
        Arc<AtomicBool>,
        std::thread::JoinHandle<std::io::Result<()>>,
    ) {
        let listener = bind(0).unwrap();
        let addr = listener.local_addr().unwrap();
        let viewer = Arc::new(Viewer::new(entries));
        let stop = Arc::new(AtomicBool::new(false));
        let server = {
            let stop = stop.clone();
            std::thread::spawn(move || serve(listener, viewer, &stop))
        };
        (addr, stop, server)
    }

    #[test]
    fn only_loopback_host_names_are_answered() {
        for ok in [
            "localhost",
            "localhost:8765",
            "127.0.0.1:80",
            "127.1.2.3",
            "[::1]:8765",
            "LOCALHOST.",
            "a.localhost",
        ] {
            assert!(is_loopback_host(ok), "{ok}");
        }
        for foreign in [
            "evil.example:8765",
            "192.168.1.2",
            "localhost.evil.example",
            "[::2]",
            "",
            "127.0.0.1.evil.example",
        ] {
            assert!(!is_loopback_host(foreign), "{foreign}");
        }
        let (addr, stop, server) = start(Vec::new());
        let (status, body) = get_from(addr, "/api/replays", "attacker.example:8765");
        assert!(
            status.contains("403") && body.contains("attacker.example"),
            "{status} {body}"
        );
        assert!(get_from(addr, "/api/replays", "127.0.0.1:8765").0.contains("200"));
        stop.store(true, Ordering::SeqCst);
        server.join().unwrap().unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_thousand_mixed_requests_with_panicking_makers_and_a_fifo_leave_it_serving() {
        let dir = std::env::temp_dir().join(format!("vsrlab-viewer-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let fifo = dir.join("hang.replay.json");
        assert!(std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success());
        let good = dir.join("good.replay.json");
        std::fs::write(&good, b"{\"format\":\"vsrlab-replay\"}").unwrap();
        let entries = vec![
            ViewerEntry {
                name: "good".into(),
                source: ReplaySource::File(good),
                shown: true,
            },
            ViewerEntry {
                name: "fifo".into(),
                source: ReplaySource::File(fifo),
                shown: false,
            },
            ViewerEntry {
                name: "panics".into(),
                source: ReplaySource::Make(Box::new(|| panic!("a body with no voxels"))),
                shown: false,
            },
            ViewerEntry {
                name: "fails".into(),
                source: ReplaySource::Make(Box::new(|| Err("the episode became non-finite".into()))),
                shown: false,
            },
        ];
        let (addr, stop, server) = start(entries);
        let cases: [(&str, &str, &str); 8] = [
            ("/replay/0", "localhost", "200"),
            ("/replay/1", "localhost", "not a regular file"),
            ("/replay/2", "localhost", "a body with no voxels"),
            ("/replay/3", "127.0.0.1", "non-finite"),
            ("/replay/9", "localhost", "404"),
            ("/api/replays", "rebound.example", "403"),
            ("/../../etc/passwd", "localhost", "404"),
            ("/", "[::1]:1", "200"),
        ];
        let workers: Vec<_> = (0..4)
            .map(|w| {
                std::thread::spawn(move || {
                    for i in 0..250 {
                        let (target, host, expect) = cases[(i * 7 + w) % cases.len()];
                        let (status, body) = get_from(addr, target, host);
                        assert!(
                            status.contains(expect) || body.contains(expect),
                            "{target}: {status} {body}"
                        );
                    }
                })
            })
            .collect();
        for w in workers {
            w.join().unwrap();
        }
        stop.store(true, Ordering::SeqCst);
        server.join().unwrap().unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn serves_the_page_and_replays_and_nothing_else() {
        let entries = vec![
            ViewerEntry {
                name: "made".into(),
                source: ReplaySource::Make(Box::new(|| Ok(b"{\"format\":\"vsrlab-replay\"}".to_vec()))),
                shown: true,
            },
            ViewerEntry {
                name: "broken".into(),
                source: ReplaySource::Make(Box::new(|| Err("cannot simulate".into()))),
                shown: false,
            },
        ];
        let listener = bind(0).unwrap();
        let addr = listener.local_addr().unwrap();
        assert!(addr.ip().is_loopback());
        let viewer = Arc::new(Viewer::new(entries));
        let stop = Arc::new(AtomicBool::new(false));
        let server = {
            let stop = stop.clone();
            std::thread::spawn(move || serve(listener, viewer, &stop))
        };
        let (status, body) = get(addr, "/");
        assert!(status.contains("200"), "{status}");
        assert!(body.contains("<canvas") || body.contains("viewer.js"));
        let (status, body) = get(addr, "/api/replays");
        assert!(status.contains("200"));
        assert!(
            body.contains("\"/replay/1\"") && body.contains("\"shown\":false"),
            "{body}"
        );
        assert_eq!(get(addr, "/replay/0").1, "{\"format\":\"vsrlab-replay\"}");
        let (status, body) = get(addr, "/replay/1");
        assert!(status.contains("500") && body.contains("cannot simulate"));
        for outside in [
            "/replay/2",
            "/../Cargo.toml",
            "/replay/../../etc/passwd",
            "/%2e%2e/etc/passwd",
            "/src/lib.rs",
        ] {
            assert!(get(addr, outside).0.contains("404"), "{outside}");
        }
        stop.store(true, Ordering::SeqCst);
        server.join().unwrap().unwrap();
    }
}
