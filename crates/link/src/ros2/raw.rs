//! Listening to a DDS domain without knowing its types, for `navdeck ros2 topics`: a
//! participant that reads what discovery found and subscribes to every published topic
//! with a reader that keeps each sample's serialized bytes (no type needed), best effort
//! and volatile so that it matches every writer, to count how often samples arrive.
//! Time is passed in (session seconds): the caller owns the clock.

use super::config::Ros2Config;
use super::graph::{self, Endpoint};
use super::participant::{Joined, fail, join};
use crate::LinkError;
use ros2_client::dds::rustdds::no_key::{DataReader, Decode, DefaultDecoder, DeserializerAdapter};
use ros2_client::dds::rustdds::{
    DomainParticipant, QosPolicies, QosPolicyBuilder, RTPSEntity, ReadCondition,
    RepresentationIdentifier, Subscriber, TopicKind, policy,
};
use ros2_client::{Context, Node};
use std::collections::BTreeMap;

/// Samples kept by a rate-taking reader between two polls (it is drained every poll).
const READER_DEPTH: i32 = 100;

/// Samples taken from one reader in one poll at most.
const MAX_TAKE: usize = 1000;

/// One sample as it crossed the wire: its serialized bytes, type unknown.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RawSample(pub Vec<u8>);

/// Reads any payload as its bytes: a `DeserializerAdapter` that decodes nothing.
pub struct RawAdapter;

/// The decoder `RawAdapter` uses: it copies the bytes.
#[derive(Clone, Copy, Debug)]
pub struct RawDecoder;

/// Every data representation of RTPS 2.5 Table 10.3 (plain, parameter-list and XTypes
/// CDR, either byte order): the bytes are kept whatever they encode.
const ANY_ENCODING: [RepresentationIdentifier; 17] = [
    RepresentationIdentifier::CDR_BE,
    RepresentationIdentifier::CDR_LE,
    RepresentationIdentifier::PL_CDR_BE,
    RepresentationIdentifier::PL_CDR_LE,
    RepresentationIdentifier::CDR2_BE,
    RepresentationIdentifier::CDR2_LE,
    RepresentationIdentifier::PL_CDR2_BE,
    RepresentationIdentifier::PL_CDR2_LE,
    RepresentationIdentifier::D_CDR_BE,
    RepresentationIdentifier::D_CDR_LE,
    RepresentationIdentifier::XML,
    RepresentationIdentifier::XCDR2_BE,
    RepresentationIdentifier::XCDR2_LE,
    RepresentationIdentifier::D_CDR2_BE,
    RepresentationIdentifier::D_CDR2_LE,
    RepresentationIdentifier::PL_XCDR2_BE,
    RepresentationIdentifier::PL_XCDR2_LE,
];

impl DeserializerAdapter<RawSample> for RawAdapter {
    type Error = std::convert::Infallible;
    type Decoded = RawSample;

    fn supported_encodings() -> &'static [RepresentationIdentifier] {
        &ANY_ENCODING
    }

    fn transform_decoded(decoded: RawSample) -> RawSample {
        decoded
    }
}

impl DefaultDecoder<RawSample> for RawAdapter {
    type Decoder = RawDecoder;
    const DECODER: RawDecoder = RawDecoder;
}

impl<'de> Decode<'de, RawSample> for RawDecoder {
    type Error = std::convert::Infallible;

    fn decode_bytes(
        self,
        input_bytes: &'de [u8],
        _encoding: RepresentationIdentifier,
    ) -> Result<RawSample, Self::Error> {
        Ok(RawSample(input_bytes.to_vec()))
    }
}

/// How many samples arrived and when the first and last did (session seconds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arrivals {
    /// When the reader was opened.
    pub opened: f64,
    pub count: u64,
    pub first: Option<f64>,
    pub last: Option<f64>,
    /// Bytes received, serialized.
    pub bytes: u64,
}

impl Arrivals {
    /// Nothing yet, the reader opened at `opened`.
    pub fn new(opened: f64) -> Self {
        Self {
            opened,
            count: 0,
            first: None,
            last: None,
            bytes: 0,
        }
    }

    /// `n` samples of `bytes` in all were taken at `now`.
    pub fn note(&mut self, now: f64, n: u64, bytes: u64) {
        if n == 0 {
            return;
        }
        self.first.get_or_insert(now);
        self.last = Some(now);
        self.count += n;
        self.bytes += bytes;
    }

    /// Samples a second at `now`: the intervals between the first and the last arrival
    /// (as `ros2 topic hz` takes them), or, with fewer than two seen apart, the count
    /// over the time the reader has listened.
    pub fn rate(&self, now: f64) -> f64 {
        match (self.first, self.last) {
            (Some(first), Some(last)) if self.count >= 2 && last > first => {
                (self.count - 1) as f64 / (last - first)
            }
            _ => {
                let listened = now - self.opened;
                if listened > 0.0 {
                    self.count as f64 / listened
                } else {
                    0.0
                }
            }
        }
    }
}

/// The namespaces of the robots `participant` has discovered on its domain
/// (`graph::robots`), leaving out its own endpoints: what a fleet's console offers to add.
pub fn robots_seen(participant: &Context) -> Vec<String> {
    let p = participant.domain_participant();
    let own = p.guid().prefix;
    let mut ends: Vec<Endpoint> = (p.discovered_writers().iter())
        .filter(|w| w.publication_topic_data.key.prefix != own)
        .map(Endpoint::from_writer)
        .collect();
    ends.extend(
        (p.discovered_readers().iter())
            .filter(|r| r.subscription_topic_data.key().prefix != own)
            .map(Endpoint::from_reader),
    );
    (graph::robots::robots(&ends, &BTreeMap::new()).into_iter())
        .map(|r| r.namespace)
        .collect()
}

/// A reader that keeps bytes, on one topic, and what it counted.
struct RateReader {
    reader: DataReader<RawSample, RawAdapter>,
    arrivals: Arrivals,
}

/// A participant on the domain that watches discovery and measures published topics.
pub struct Listener {
    /// Owns the participant: kept for as long as the listener lives.
    context: Context,
    _node: Node,
    subscriber: Subscriber,
    /// Endpoints of this participant (its own readers, its node's) carry this prefix.
    own: ros2_client::dds::rustdds::GUID,
    /// Only topics `graph::shown` with this are measured.
    all: bool,
    readers: BTreeMap<String, RateReader>,
    /// Topics whose reader could not be opened, and why.
    failed: BTreeMap<String, String>,
}

impl Listener {
    /// Joins `domain` on the configured interfaces (`[ros2] interfaces`), as the link
    /// does, with a node named `navdeck_topics`.
    pub fn join(config: &Ros2Config, domain: u16, all: bool) -> Result<Listener, LinkError> {
        let Joined { context, node, .. } = join(config, domain, "navdeck_topics")?;
        let participant = context.domain_participant();
        let subscriber = participant
            .create_subscriber(&rate_qos())
            .map_err(|e| fail("create a DDS subscriber", e))?;
        let own = participant.guid();
        Ok(Listener {
            context,
            _node: node,
            subscriber,
            own,
            all,
            readers: BTreeMap::new(),
            failed: BTreeMap::new(),
        })
    }

    fn participant(&self) -> DomainParticipant {
        self.context.domain_participant()
    }

    /// Opens a reader on every newly published topic (of the writers' type) and counts
    /// what arrived on the others, at `now`.
    pub fn poll(&mut self, now: f64, discover: bool) {
        if discover {
            let participant = self.participant();
            for w in participant.discovered_writers() {
                let data = &w.publication_topic_data;
                let topic = &data.topic_name;
                if data.key.prefix == self.own.prefix
                    || !graph::shown(topic, self.all)
                    || self.readers.contains_key(topic)
                    || self.failed.contains_key(topic)
                {
                    continue;
                }
                match self.open(&participant, topic, &data.type_name) {
                    Ok(reader) => {
                        let arrivals = Arrivals::new(now);
                        self.readers
                            .insert(topic.clone(), RateReader { reader, arrivals });
                    }
                    Err(why) => {
                        self.failed.insert(topic.clone(), why);
                    }
                }
            }
        }
        for r in self.readers.values_mut() {
            // An unreadable sample still arrived; a failed take counts nothing.
            if let Ok(samples) = r.reader.take(MAX_TAKE, ReadCondition::any()) {
                let bytes = samples.iter().map(|s| s.value().0.len() as u64).sum();
                r.arrivals.note(now, samples.len() as u64, bytes);
            }
        }
    }

    fn open(
        &self,
        participant: &DomainParticipant,
        topic: &str,
        dds_type: &str,
    ) -> Result<DataReader<RawSample, RawAdapter>, String> {
        let qos = rate_qos();
        let t = participant
            .create_topic(
                topic.to_string(),
                dds_type.to_string(),
                &qos,
                TopicKind::NoKey,
            )
            .map_err(|e| format!("cannot create topic {topic}: {e:?}"))?;
        self.subscriber
            .create_datareader_no_key::<RawSample, RawAdapter>(&t, Some(qos))
            .map_err(|e| format!("cannot read {topic}: {e:?}"))
    }

    /// Every endpoint other participants announced (this one's left out).
    pub fn endpoints(&self) -> Vec<Endpoint> {
        let participant = self.participant();
        let writers = participant.discovered_writers();
        let readers = participant.discovered_readers();
        let mut out: Vec<Endpoint> = (writers.iter())
            .filter(|w| w.publication_topic_data.key.prefix != self.own.prefix)
            .map(Endpoint::from_writer)
            .collect();
        out.extend(
            (readers.iter())
                .filter(|r| r.subscription_topic_data.key().prefix != self.own.prefix)
                .map(Endpoint::from_reader),
        );
        out
    }

    /// What each measured topic's reader counted, by DDS topic name.
    pub fn arrivals(&self) -> BTreeMap<String, Arrivals> {
        (self.readers.iter())
            .map(|(topic, r)| (topic.clone(), r.arrivals))
            .collect()
    }

    /// Samples a second on each measured topic at `now`, by DDS topic name.
    pub fn rates(&self, now: f64) -> BTreeMap<String, f64> {
        (self.readers.iter())
            .map(|(topic, r)| (topic.clone(), r.arrivals.rate(now)))
            .collect()
    }

    /// Topics that could not be measured, and why.
    pub fn failures(&self) -> &BTreeMap<String, String> {
        &self.failed
    }
}

/// Best effort, volatile, keep-last `READER_DEPTH`: asks for the least, so every writer
/// matches it whatever it offers (DDS 1.4, 2.2.3 "requested vs offered").
fn rate_qos() -> QosPolicies {
    QosPolicyBuilder::new()
        .reliability(policy::Reliability::BestEffort)
        .durability(policy::Durability::Volatile)
        .history(policy::History::KeepLast {
            depth: READER_DEPTH,
        })
        .build()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn any_payload_is_kept_as_its_bytes() {
        let bytes = [0u8, 1, 0, 0, 42, 0, 0, 0];
        for encoding in ANY_ENCODING {
            let got = RawAdapter::from_bytes(&bytes, encoding).unwrap();
            assert_eq!(got, RawSample(bytes.to_vec()));
        }
    }

    #[test]
    fn twenty_a_second_reads_twenty_whatever_the_poll() {
        // A 20 Hz topic polled every 30 ms: batches of zero, one or two samples.
        let mut a = Arrivals::new(0.0);
        let mut next = 0.3;
        for k in 1..=100 {
            let now = k as f64 * 0.03;
            let mut n = 0;
            while next <= now {
                n += 1;
                next += 0.05;
            }
            a.note(now, n, 10 * n);
        }
        let rate = a.rate(3.0);
        assert!((rate - 20.0).abs() < 1.0, "{rate}");
        // Samples at 0.30, 0.35, ... 3.00 s: 55, the first and the last taken on time.
        assert_eq!(a.count, 55);
        assert_eq!(a.bytes, 550);
    }

    #[test]
    fn few_samples_are_counted_over_the_time_listened() {
        let mut a = Arrivals::new(1.0);
        assert_eq!(a.rate(3.0), 0.0);
        assert_eq!(a.rate(1.0), 0.0);
        // One latched map in two seconds.
        a.note(1.5, 1, 100);
        assert_eq!(a.rate(3.0), 0.5);
        // Two in one batch: no interval to take.
        let mut b = Arrivals::new(0.0);
        b.note(0.5, 2, 0);
        assert_eq!(b.rate(2.0), 1.0);
    }
}
