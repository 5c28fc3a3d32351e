//! Where the panel's long computations run: the plots' integrals, the 3D
//! lobe, the θ_h × θ_d image and a fit run now. They run on threads of
//! their own at a lower scheduling priority (nice +10), and their
//! parallel loops on a pool that leaves one core to the window, so the UI
//! thread (and lavapipe's rasterizer threads, which draw its frames)
//! never waits behind them. Before, with a measured material the
//! albedo curve's rayon loop took every core while lavapipe compiled the
//! first frame's shaders, and the window stayed black for 9–35 s.

use std::sync::OnceLock;

/// Niceness of the background threads (0 is the window's, 19 the lowest).
const NICE: i32 = 10;

/// The environment variable that holds the background: with it set (to
/// anything but empty or `0`), every job first occupies every thread of
/// [`pool`] and never finishes, as a measured material's albedo curve
/// occupies them for a minute. A scripted viewer run must still draw its
/// frames and exit (`tests/viewer_out_of_the_way.rs`); were the pool
/// rayon's global one, the first frame's parallel loops would wait
/// forever. Each held job says so on stderr.
pub const HOLD_ENV: &str = "GONIO_HOLD_BACKGROUND";

/// Runs `job` on a new low-priority thread, its parallel loops on
/// [`pool`].
pub fn spawn(job: impl FnOnce() + Send + 'static) {
    let hold = std::env::var(HOLD_ENV).is_ok_and(|v| !v.is_empty() && v != "0");
    if hold {
        eprintln!("gonio view: a background job is held ({HOLD_ENV} is set); it will not finish");
    }
    std::thread::spawn(move || {
        lower_priority();
        pool().install(|| {
            if hold {
                // Every thread of the pool parks for good.
                let _ = rayon::broadcast(|_| park_for_good());
            }
            job()
        });
    });
}

/// Parks the calling thread and never returns ([`HOLD_ENV`]).
fn park_for_good() {
    loop {
        std::thread::park();
    }
}

/// The background pool: one thread fewer than the machine has cores (at
/// least one), each at low priority.
pub fn pool() -> &'static rayon::ThreadPool {
    static POOL: OnceLock<rayon::ThreadPool> = OnceLock::new();
    POOL.get_or_init(|| {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        rayon::ThreadPoolBuilder::new()
            .num_threads(cores.saturating_sub(1).max(1))
            .thread_name(|i| format!("gonio-background-{i}"))
            .start_handler(|_| lower_priority())
            .build()
            .expect("a thread pool of at least one thread starts")
    })
}

/// Lowers the calling thread's scheduling priority (Linux: `setpriority`
/// on the thread id, which is per thread there; elsewhere nothing).
#[allow(unsafe_code)] // Two FFI calls, no memory handed over (see below).
fn lower_priority() {
    #[cfg(target_os = "linux")]
    // SAFETY: `gettid` has no preconditions; `setpriority` on our own
    // thread id changes only this thread's niceness, and its failure
    // (a sandbox forbidding it) leaves the priority as it was.
    unsafe {
        let tid = libc::syscall(libc::SYS_gettid) as libc::id_t;
        libc::setpriority(libc::PRIO_PROCESS, tid, NICE);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(unsafe_code)] // Reads the niceness: FFI, no memory handed over.
    fn background_jobs_run_at_a_lower_priority() {
        let (tx, rx) = std::sync::mpsc::channel();
        spawn(move || {
            // SAFETY: reads this thread's niceness.
            #[cfg(target_os = "linux")]
            let nice = unsafe {
                libc::getpriority(
                    libc::PRIO_PROCESS,
                    libc::syscall(libc::SYS_gettid) as libc::id_t,
                )
            };
            #[cfg(not(target_os = "linux"))]
            let nice = NICE;
            let in_pool = rayon::current_thread_index().is_some();
            let _ = tx.send((nice, in_pool));
        });
        let (nice, in_pool) = rx.recv().unwrap();
        assert!(nice >= NICE.min(19), "niceness {nice}");
        assert!(in_pool);
    }

    /// A background job whose parallel loop occupies every thread it has
    /// does not hold up a parallel loop of the UI thread (the GPU's
    /// measured table): they are on different pools. Before, both were on
    /// rayon's global pool and the first frame waited for the albedo
    /// curve. The receive's limit only detects that wait; it
    /// measures nothing.
    #[test]
    fn a_busy_background_does_not_hold_up_the_ui_threads_loops() {
        use rayon::prelude::*;
        let (release_tx, release_rx) = std::sync::mpsc::channel::<()>();
        let release_rx = std::sync::Mutex::new(release_rx);
        let (started_tx, started_rx) = std::sync::mpsc::channel();
        spawn(move || {
            let threads = rayon::current_num_threads();
            (0..threads).into_par_iter().for_each(|_| {
                let _ = started_tx.send(());
                // Every pool thread waits here until released.
                let _ = release_rx.lock().map(|rx| rx.recv());
            });
        });
        started_rx.recv().unwrap();
        let (done_tx, done_rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let sum: u64 = (0..1000u64).into_par_iter().sum();
            let _ = done_tx.send(sum);
        });
        let done = done_rx.recv_timeout(std::time::Duration::from_secs(60));
        for _ in 0..pool().current_num_threads() {
            let _ = release_tx.send(());
        }
        assert_eq!(
            done,
            Ok(499_500),
            "the global pool waited for the background"
        );
    }
}
