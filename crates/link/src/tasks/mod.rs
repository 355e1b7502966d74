//! The one tokio runtime the links' I/O runs on: every DDS reader of every robot, each
//! serial port's worker and the recorder's writer are tasks on it, so a fleet of ten adds
//! no thread per robot. Work that can only block (a serial port's timed request and reply,
//! file writes) goes to the runtime's blocking pool. The console hears from the tasks
//! through `wake`; the pilot and the core never see the runtime.

pub mod wake;

use crate::LinkError;
use std::future::Future;
use std::sync::OnceLock;
use tokio::runtime::{Builder, Handle, Runtime};
use tokio::task::JoinHandle;

/// Threads that run the async tasks. The tasks only move messages between DDS and
/// channels, so one serves a fleet (see the README's fleet figures).
const WORKERS: usize = 1;

static RUNTIME: OnceLock<Result<Runtime, String>> = OnceLock::new();

/// The runtime, started on first use.
pub fn handle() -> Result<Handle, LinkError> {
    let built = RUNTIME.get_or_init(|| {
        Builder::new_multi_thread()
            .worker_threads(WORKERS)
            .thread_name("navdeck-io")
            .enable_time()
            .build()
            .map_err(|e| e.to_string())
    });
    match built {
        Ok(runtime) => Ok(runtime.handle().clone()),
        Err(e) => Err(LinkError::Lost(format!(
            "cannot start the I/O runtime: {e}"
        ))),
    }
}

/// Runs `task` on the runtime.
pub fn spawn<F>(task: F) -> Result<JoinHandle<F::Output>, LinkError>
where
    F: Future + Send + 'static,
    F::Output: Send + 'static,
{
    Ok(handle()?.spawn(task))
}

/// Runs blocking `work` on the runtime's blocking pool.
pub fn spawn_blocking<F, R>(work: F) -> Result<JoinHandle<R>, LinkError>
where
    F: FnOnce() -> R + Send + 'static,
    R: Send + 'static,
{
    Ok(handle()?.spawn_blocking(work))
}

/// Waits for a task from synchronous code (a link's shutdown); None if it panicked or was
/// aborted.
pub fn join<R>(task: JoinHandle<R>) -> Option<R> {
    let handle = handle().ok()?;
    // A blocking wait must not run on the runtime's own threads.
    if Handle::try_current().is_ok() {
        task.abort();
        return None;
    }
    handle.block_on(task).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tasks_and_blocking_work_run_and_are_joined() {
        let task = spawn(async { 2 + 2 }).unwrap();
        assert_eq!(join(task), Some(4));
        let work = spawn_blocking(|| "done").unwrap();
        assert_eq!(join(work), Some("done"));
    }

    #[test]
    fn a_panicking_task_joins_as_none() {
        let task = spawn(async { panic!("a task's own failure") }).unwrap();
        assert_eq!(join::<()>(task), None);
    }
}
