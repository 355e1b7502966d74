//! A subscription read by a task on the links' runtime (`tasks`): each message is taken
//! from DDS as it arrives and waits here, in order, for the console's next poll. When the
//! console falls behind, the task waits and DDS keeps the newest per the topic's QoS depth,
//! as a ROS 2 subscriber's queue does.

use crate::Notice;
use crate::tasks::{self, wake};
use ros2_client::Subscription;
use serde::de::DeserializeOwned;
use std::time::Duration;
use tokio::runtime::Handle;
use tokio::sync::mpsc;
use tokio::task::JoinHandle;
use tokio::time;

/// Messages waiting at most: a flood cannot stall the console's poll.
pub const MAX_WAITING: usize = 1000;

/// Whether a message should wake the console at once, or wait for its tick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Urgency {
    /// Sensor streams: taken at the control tick.
    Tick,
    /// What the console acts on when it comes (a goal, a pose estimate, a log line).
    Wake,
}

enum Arrival<M> {
    Message(M),
    Unreadable(String),
}

/// One topic's messages, gathered by a task.
pub struct Inbox<M> {
    waiting: mpsc::Receiver<Arrival<M>>,
    task: JoinHandle<()>,
}

impl<M: DeserializeOwned + Send + Sync + 'static> Inbox<M> {
    /// Starts reading `subscription` on the runtime.
    pub fn read(subscription: Subscription<M>, urgency: Urgency) -> Result<Self, crate::LinkError> {
        let (sender, waiting) = mpsc::channel(MAX_WAITING);
        let task = tasks::spawn(async move {
            loop {
                let arrival = match subscription.async_take().await {
                    Ok((message, _)) => Arrival::Message(message),
                    Err(e) => Arrival::Unreadable(format!("{e:?}")),
                };
                let unreadable = matches!(arrival, Arrival::Unreadable(_));
                if sender.send(arrival).await.is_err() {
                    return;
                }
                if urgency == Urgency::Wake || unreadable {
                    wake::notify();
                }
            }
        })?;
        Ok(Self { waiting, task })
    }

    /// Every message waiting, oldest first; an unreadable one is a warning naming `topic`.
    pub fn take_all(&mut self, topic: &str, notices: &mut Vec<Notice>) -> Vec<M> {
        let mut out = Vec::new();
        for _ in 0..MAX_WAITING {
            let Ok(arrival) = self.waiting.try_recv() else {
                break;
            };
            accept(arrival, topic, &mut out, notices);
        }
        out
    }

    /// As `take_all`, but when nothing is waiting, waits up to `timeout` for the first
    /// message. For a reader outside the runtime (a camera's frame grabber); on the
    /// runtime's own threads it does not wait.
    pub fn wait_all(
        &mut self,
        topic: &str,
        timeout: Duration,
        notices: &mut Vec<Notice>,
    ) -> Vec<M> {
        let mut out = self.take_all(topic, notices);
        if !out.is_empty() || !notices.is_empty() || Handle::try_current().is_ok() {
            return out;
        }
        let Ok(runtime) = tasks::handle() else {
            return out;
        };
        // The timer is made inside the runtime: it needs the runtime's clock.
        let waited = runtime.block_on(async { time::timeout(timeout, self.waiting.recv()).await });
        if let Ok(Some(first)) = waited {
            accept(first, topic, &mut out, notices);
            out.extend(self.take_all(topic, notices));
        }
        out
    }
}

fn accept<M>(arrival: Arrival<M>, topic: &str, out: &mut Vec<M>, notices: &mut Vec<Notice>) {
    match arrival {
        Arrival::Message(m) => out.push(m),
        Arrival::Unreadable(e) => {
            notices.push(Notice::warn(format!("ROS 2: unreadable {topic}: {e}")))
        }
    }
}

impl<M> Drop for Inbox<M> {
    fn drop(&mut self) {
        // The subscription goes with its task.
        self.task.abort();
    }
}
