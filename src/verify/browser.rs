//! The browser paths: emitted code run where web pages run it, in headless Chromium (the
//! Debian package `chromium`). WGSL goes through WebGPU, that is Dawn and its WGSL
//! compiler Tint (`wgsl/tint`), GLSL as GLSL ES 3.00 through WebGL 2, that is ANGLE
//! (`glsl/angle`). Without a GPU both run on SwiftShader, Chromium's own Vulkan.
//!
//! One browser and one page serve a whole run: the page (`web/harness.js` over
//! `web/runner.js`) asks a server on 127.0.0.1 for the next job, runs it and posts the
//! output words back, so the verify workers hand it jobs as they would to a device. Why a
//! page in Chromium rather than Dawn for Node.js: the one package gives WebGPU, WebGL 2
//! and the `verify --web` page the same browser users run, with nothing fetched at run
//! time (docs/design/portability.md, "Browsers").

use anyhow::{Context, Result, anyhow, bail};
use std::collections::{HashMap, VecDeque};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

/// The page's job runner and the harness that feeds it.
pub const RUNNER_JS: &str = include_str!("web/runner.js");
const HARNESS_JS: &str = include_str!("web/harness.js");

/// Where Debian's package puts the browser.
const CHROMIUM: &str = "/usr/bin/chromium";

/// How long one job may take, compile included, before the run gives up on the browser.
const JOB_TIMEOUT: Duration = Duration::from_secs(300);

/// How long the page has to load and say what runs it.
const HELLO_TIMEOUT: Duration = Duration::from_secs(90);

/// The API a job runs through.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Api {
    /// `source` is a selecting WGSL kernel (`crate::verify::gpu`'s binding contract);
    /// override 0 picks the function.
    WebGpu,
    /// `source` is a GLSL ES 3.00 vertex shader of one function
    /// ([`crate::emit::lang::glsl::Glsl::webgl_kernel`]).
    WebGl,
}

impl Api {
    /// The page's name for it.
    fn name(self) -> &'static str {
        match self {
            Api::WebGpu => "webgpu",
            Api::WebGl => "webgl",
        }
    }
}

/// A whole GLSL include as the GLSL ES 3.00 vertex shader ANGLE compiles for
/// [`Browser::compile`]: the include and an empty `main`. ANGLE translates every function,
/// called or not.
pub fn webgl_include_shader(include: &str) -> String {
    format!(
        "#version 300 es\nprecision highp float;\nprecision highp int;\n{include}\n\
         void main() {{\n    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);\n}}\n"
    )
}

/// One function's run in the page.
pub struct Job<'a> {
    pub api: Api,
    /// Jobs with the same key share `source`: the page compiles it once.
    pub key: u64,
    pub source: &'a str,
    pub selector: u32,
    pub input: &'a [u32],
    pub in_words: usize,
    pub out_words: usize,
}

type Reply = Result<Vec<u32>, String>;

struct State {
    queue: VecDeque<(u64, Vec<u8>)>,
    waiting: HashMap<u64, mpsc::Sender<Reply>>,
    next: u64,
    /// What the page said runs it (WebGPU adapter, WebGL renderer), once it has loaded.
    hello: Option<serde_json::Value>,
    /// What a `verify --web` page posted to `/report`.
    report: Option<String>,
    closed: bool,
}

/// A headless Chromium with the harness page open, and the server it talks to.
pub struct Browser {
    state: Arc<(Mutex<State>, Condvar)>,
    child: Mutex<Child>,
    server: Arc<tiny_http::Server>,
    _profile: tempfile::TempDir,
    log: std::path::PathBuf,
}

fn respond(req: tiny_http::Request, status: u16, body: Vec<u8>, ty: &str) {
    let header =
        tiny_http::Header::from_bytes(&b"Content-Type"[..], ty.as_bytes()).expect("a valid header");
    let r = tiny_http::Response::from_data(body)
        .with_status_code(status)
        .with_header(header);
    let _ = req.respond(r);
}

fn page() -> String {
    format!(
        "<!doctype html>\n<meta charset=\"utf-8\">\n<title>unitpack verify</title>\n\
         <script>\n{RUNNER_JS}\n</script>\n<script>\n{HARNESS_JS}\n</script>\n"
    )
}

impl Browser {
    /// Starts the server and the browser. Fails, naming the package, when Chromium is not
    /// installed; the page has not necessarily loaded yet ([`Browser::adapters`] waits).
    pub fn start() -> Result<Browser> {
        Self::start_with(page())
    }

    /// [`Browser::start`] with another page at `/`: a `verify --web` page, whose report
    /// [`Browser::report`] waits for.
    pub fn start_with(page: String) -> Result<Browser> {
        if !std::path::Path::new(CHROMIUM).exists() {
            bail!(
                "the browser paths (wgsl/tint, glsl/angle) need headless Chromium at {CHROMIUM}: \
                 install the Debian package `chromium`"
            );
        }
        let server = Arc::new(
            tiny_http::Server::http("127.0.0.1:0")
                .map_err(|e| anyhow!("cannot listen on 127.0.0.1: {e}"))?,
        );
        let port = server
            .server_addr()
            .to_ip()
            .context("the server's address")?
            .port();
        let state = Arc::new((
            Mutex::new(State {
                queue: VecDeque::new(),
                waiting: HashMap::new(),
                next: 0,
                hello: None,
                report: None,
                closed: false,
            }),
            Condvar::new(),
        ));
        {
            let (server, state) = (server.clone(), state.clone());
            std::thread::spawn(move || serve(&server, &state, &page));
        }
        let profile = tempfile::tempdir().context("a profile folder for Chromium")?;
        let log = profile.path().join("chromium.log");
        let log_file = std::fs::File::create(&log).context("Chromium's log file")?;
        let mut cmd = Command::new(CHROMIUM);
        cmd.args([
            "--headless=new",
            "--no-sandbox",
            "--enable-unsafe-webgpu",
            // Chromium keeps WebGL on SwiftShader behind this flag where there is no GPU.
            "--enable-unsafe-swiftshader",
            "--no-first-run",
            "--no-default-browser-check",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-default-apps",
            "--disable-gpu-watchdog",
            "--disable-renderer-backgrounding",
            "--disable-background-timer-throttling",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("http://127.0.0.1:{port}/"))
        .stdin(Stdio::null())
        .stdout(log_file.try_clone().context("Chromium's log file")?)
        .stderr(log_file);
        #[cfg(target_os = "linux")]
        {
            use std::os::unix::process::CommandExt;
            // SAFETY: prctl is async-signal-safe; it only asks the kernel to end the
            // browser when the verifier ends, however it ends.
            unsafe {
                cmd.pre_exec(|| {
                    libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL);
                    Ok(())
                });
            }
        }
        let child = cmd
            .spawn()
            .with_context(|| format!("starting {CHROMIUM}"))?;
        Ok(Browser {
            state,
            child: Mutex::new(child),
            server,
            _profile: profile,
            log,
        })
    }

    /// The tail of Chromium's own log, for errors.
    fn log_tail(&self) -> String {
        let text = std::fs::read_to_string(&self.log).unwrap_or_default();
        let lines: Vec<&str> = text
            .lines()
            .filter(|l| !l.contains("dbus") && !l.trim().is_empty())
            .collect();
        lines[lines.len().saturating_sub(12)..].join("\n")
    }

    fn exited(&self) -> Option<String> {
        let mut child = self.child.lock().expect("the child");
        match child.try_wait() {
            Ok(Some(status)) => Some(format!(
                "headless Chromium exited ({status}); its log ends:\n{}",
                self.log_tail()
            )),
            _ => None,
        }
    }

    /// What the page reports runs its jobs: the WebGPU adapter and the WebGL renderer,
    /// waiting for the page to load.
    pub fn adapters(&self) -> Result<serde_json::Value> {
        let (lock, cv) = &*self.state;
        let start = Instant::now();
        let mut st = lock.lock().expect("state");
        while st.hello.is_none() {
            if let Some(why) = self.exited() {
                bail!(why);
            }
            if start.elapsed() > HELLO_TIMEOUT {
                bail!(
                    "headless Chromium did not load the verification page in {} s; its log ends:\n{}",
                    HELLO_TIMEOUT.as_secs(),
                    self.log_tail()
                );
            }
            st = cv
                .wait_timeout(st, Duration::from_millis(200))
                .expect("state")
                .0;
        }
        Ok(st.hello.clone().expect("said hello"))
    }

    /// The report a `verify --web` page posts when it has run everything, waiting up to
    /// `timeout` for it.
    pub fn report(&self, timeout: Duration) -> Result<String> {
        let (lock, cv) = &*self.state;
        let start = Instant::now();
        let mut st = lock.lock().expect("state");
        while st.report.is_none() {
            if let Some(why) = self.exited() {
                bail!(why);
            }
            if start.elapsed() > timeout {
                bail!(
                    "the page posted no report in {} s; Chromium's log ends:\n{}",
                    timeout.as_secs(),
                    self.log_tail()
                );
            }
            st = cv
                .wait_timeout(st, Duration::from_millis(200))
                .expect("state")
                .0;
        }
        Ok(st.report.clone().expect("posted"))
    }

    /// A one-line description of the adapters, for the report.
    pub fn describe(&self) -> String {
        match self.adapters() {
            Ok(h) => {
                let gpu = &h["webgpu"];
                let webgpu = if gpu.is_null() {
                    format!("none ({})", h["webgpu_error"].as_str().unwrap_or("?"))
                } else {
                    format!(
                        "{} {}{}",
                        gpu["vendor"].as_str().unwrap_or(""),
                        gpu["architecture"].as_str().unwrap_or(""),
                        if gpu["fallback"].as_bool() == Some(true) {
                            " (fallback adapter)"
                        } else {
                            ""
                        }
                    )
                };
                format!(
                    "WebGPU: {webgpu}; WebGL 2: {}",
                    h["webgl"].as_str().unwrap_or("none")
                )
            }
            Err(e) => format!("unavailable: {e:#}"),
        }
    }

    /// Runs `job` in the page and hands its output words to `sink`.
    pub fn run(&self, job: &Job, sink: &mut dyn FnMut(&[u32])) -> Result<()> {
        if job.in_words == 0 || job.out_words == 0 || !job.input.len().is_multiple_of(job.in_words)
        {
            bail!("a job needs whole items of at least one word in and out");
        }
        let words = self.submit(
            serde_json::json!({
                "api": job.api.name(),
                "key": job.key.to_string(),
                "source": job.source,
                "selector": job.selector,
                "in_words": job.in_words,
                "out_words": job.out_words,
            }),
            job.input,
        )?;
        let n = job.input.len() / job.in_words;
        if words.len() != n * job.out_words {
            bail!(
                "the page returned {} words for {} expected",
                words.len(),
                n * job.out_words
            );
        }
        sink(&words);
        Ok(())
    }

    /// Compiles `source` in the page and runs nothing: a WGSL module through WebGPU
    /// (Tint's validation), or a GLSL ES 3.00 vertex shader through WebGL 2 (ANGLE), where
    /// any warning in the info log fails as an error does.
    pub fn compile(&self, api: Api, source: &str) -> Result<()> {
        let words = self.submit(
            serde_json::json!({ "api": api.name(), "compile": true, "source": source }),
            &[],
        )?;
        if !words.is_empty() {
            bail!("the page returned {} words for a compilation", words.len());
        }
        Ok(())
    }

    /// Queues one job (`header` gains its id) and waits for the page's reply.
    fn submit(&self, mut header: serde_json::Value, input: &[u32]) -> Result<Vec<u32>> {
        self.adapters()?;
        let (tx, rx) = mpsc::channel();
        let (lock, cv) = &*self.state;
        {
            let mut st = lock.lock().expect("state");
            let id = st.next;
            st.next += 1;
            header["id"] = id.into();
            let header = header.to_string();
            let mut body = Vec::with_capacity(8 + header.len() + input.len() * 4);
            body.extend_from_slice(&(header.len() as u32).to_le_bytes());
            body.extend_from_slice(header.as_bytes());
            while body.len() % 4 != 0 {
                body.push(b' ');
            }
            body.extend(input.iter().flat_map(|w| w.to_le_bytes()));
            st.queue.push_back((id, body));
            st.waiting.insert(id, tx);
            cv.notify_all();
        }
        let start = Instant::now();
        let reply = loop {
            match rx.recv_timeout(Duration::from_secs(1)) {
                Ok(r) => break r,
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    if let Some(why) = self.exited() {
                        bail!(why);
                    }
                    if start.elapsed() > JOB_TIMEOUT {
                        bail!(
                            "the browser returned nothing in {} s; its log ends:\n{}",
                            JOB_TIMEOUT.as_secs(),
                            self.log_tail()
                        );
                    }
                }
                Err(mpsc::RecvTimeoutError::Disconnected) => bail!("the browser's server stopped"),
            }
        };
        reply.map_err(|e| anyhow!("{e}"))
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        {
            let (lock, cv) = &*self.state;
            lock.lock().expect("state").closed = true;
            cv.notify_all();
        }
        let mut child = self.child.lock().expect("the child");
        let _ = child.kill();
        let _ = child.wait();
        self.server.unblock();
    }
}

/// Answers the page: the harness, jobs (204 while none waits, 410 once closed), outputs
/// and errors.
fn serve(server: &tiny_http::Server, state: &Arc<(Mutex<State>, Condvar)>, page: &str) {
    for mut req in server.incoming_requests() {
        let url = req.url().to_string();
        let (lock, cv) = &**state;
        let mut body = Vec::new();
        if req.as_reader().read_to_end(&mut body).is_err() {
            continue;
        }
        let reply = |st: &mut State, id: &str, r: Reply| {
            if let Some(tx) = id.parse().ok().and_then(|id: u64| st.waiting.remove(&id)) {
                let _ = tx.send(r);
            }
        };
        match url.as_str() {
            "/" => respond(
                req,
                200,
                page.as_bytes().to_vec(),
                "text/html; charset=utf-8",
            ),
            "/report" => {
                lock.lock().expect("state").report =
                    Some(String::from_utf8_lossy(&body).into_owned());
                cv.notify_all();
                respond(req, 200, Vec::new(), "text/plain");
            }
            "/hello" => {
                let hello = serde_json::from_slice(&body).unwrap_or(serde_json::Value::Null);
                lock.lock().expect("state").hello = Some(hello);
                cv.notify_all();
                respond(req, 200, Vec::new(), "text/plain");
            }
            "/job" => {
                let mut st = lock.lock().expect("state");
                let start = Instant::now();
                while st.queue.is_empty() && !st.closed && start.elapsed() < Duration::from_secs(10)
                {
                    st = cv
                        .wait_timeout(st, Duration::from_millis(500))
                        .expect("state")
                        .0;
                }
                if st.closed {
                    drop(st);
                    respond(req, 410, Vec::new(), "text/plain");
                } else if let Some((_, job)) = st.queue.pop_front() {
                    drop(st);
                    respond(req, 200, job, "application/octet-stream");
                } else {
                    drop(st);
                    respond(req, 204, Vec::new(), "text/plain");
                }
            }
            _ => {
                if let Some(id) = url.strip_prefix("/output/") {
                    let words = body
                        .chunks_exact(4)
                        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                        .collect();
                    reply(&mut lock.lock().expect("state"), id, Ok(words));
                    respond(req, 200, Vec::new(), "text/plain");
                } else if let Some(id) = url.strip_prefix("/error/") {
                    let text = String::from_utf8_lossy(&body).into_owned();
                    reply(&mut lock.lock().expect("state"), id, Err(text));
                    respond(req, 200, Vec::new(), "text/plain");
                } else {
                    respond(req, 404, Vec::new(), "text/plain");
                }
            }
        }
    }
}
