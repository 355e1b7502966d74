//! What the mission knows about blocks and gates, read from the filter's landmarks
//! (seed 001 section 7 "Block Detection" and section 8 "Delivery Sequence").

use crate::geometry::Point2;
use crate::map::costmap::Costmap;
use crate::perception::markers::MarkerCategory;
use std::collections::BTreeMap;

/// A block's or gate's colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Colour {
    Red,
    Blue,
}

impl Colour {
    pub fn label(self) -> &'static str {
        match self {
            Colour::Red => "red",
            Colour::Blue => "blue",
        }
    }
}

/// A block: confirmed once both of its markers are on the map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block {
    pub colour: Colour,
    /// The odd marker (on the block's +x face) and the even one (+y face).
    pub markers: [u32; 2],
    /// Estimated centre.
    pub position: Point2,
    /// Both markers seen (seed 001: "register_block"); one only: a potential block.
    pub confirmed: bool,
    pub delivered: bool,
}

/// A gate: two markers on a wall, facing into the arena.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gate {
    pub colour: Colour,
    pub markers: [u32; 2],
    pub center: Point2,
    /// Unit vector from the gate into the arena, perpendicular to the marker pair.
    pub normal: (f64, f64),
}

impl Gate {
    /// The point `offset` metres in front of the gate (seed 001: "drop_location =
    /// gate_center + offset * perpendicular").
    pub fn in_front(&self, offset: f64) -> Point2 {
        Point2::new(
            self.center.x + offset * self.normal.0,
            self.center.y + offset * self.normal.1,
        )
    }

    /// Heading that faces the gate from the arena, radians.
    pub fn facing(&self) -> f64 {
        (-self.normal.1).atan2(-self.normal.0)
    }
}

/// Blocks and gates found so far.
#[derive(Clone, Debug, Default)]
pub struct Objects {
    blocks: BTreeMap<u32, Block>,
    /// By a block's odd marker: where the robot was when one of its markers was last read.
    seen_from: BTreeMap<u32, Point2>,
    gates: BTreeMap<(Colour, u32), Gate>,
}

/// Something the mission log should tell.
#[derive(Clone, Debug, PartialEq)]
pub enum Found {
    Block(Block),
    PotentialBlock(Block),
    Gate(Gate),
}

impl Objects {
    /// Reads the landmark means; `robot` decides which side of a marker pair an object lies
    /// on (the camera sees the faces turned towards it), and `map` which way a gate faces.
    /// `block_size` is the block's side.
    pub fn update(
        &mut self,
        landmarks: &BTreeMap<u32, Point2>,
        robot: Point2,
        block_size: f64,
        map: &Costmap,
    ) -> Vec<Found> {
        let mut found = Vec::new();
        for &id in landmarks.keys() {
            let category = MarkerCategory::of(id);
            let colour = match category {
                MarkerCategory::RedBlock | MarkerCategory::RedGate => Colour::Red,
                MarkerCategory::BlueBlock | MarkerCategory::BlueGate => Colour::Blue,
                _ => continue,
            };
            match category {
                MarkerCategory::RedBlock | MarkerCategory::BlueBlock => {
                    let odd = if id % 2 == 1 { id } else { id - 1 };
                    if let Some(event) = self.note_block(colour, odd, landmarks, robot, block_size)
                    {
                        found.push(event);
                    }
                }
                _ => {
                    let first = if id % 2 == 1 { id } else { id - 1 };
                    if let (Some(&a), Some(&b)) =
                        (landmarks.get(&first), landmarks.get(&(first + 1)))
                    {
                        let gate = gate_from(colour, [first, first + 1], (a, b), robot, map);
                        if self.gates.insert((colour, first), gate).is_none() {
                            found.push(Found::Gate(gate));
                        }
                    }
                }
            }
        }
        found
    }

    fn note_block(
        &mut self,
        colour: Colour,
        odd: u32,
        landmarks: &BTreeMap<u32, Point2>,
        robot: Point2,
        size: f64,
    ) -> Option<Found> {
        let previous = self.blocks.get(&odd).copied();
        if previous.is_some_and(|b| b.delivered) {
            return None;
        }
        let (a, b) = (landmarks.get(&odd), landmarks.get(&(odd + 1)));
        let (position, confirmed) = match (a, b) {
            (Some(&a), Some(&b)) => (block_centre(a, b, robot, size), true),
            (Some(&m), None) | (None, Some(&m)) => (behind(m, robot, size / 2.0), false),
            (None, None) => return None,
        };
        let block = Block {
            colour,
            markers: [odd, odd + 1],
            position,
            confirmed,
            delivered: false,
        };
        self.blocks.insert(odd, block);
        match previous {
            None if confirmed => Some(Found::Block(block)),
            None => Some(Found::PotentialBlock(block)),
            Some(p) if confirmed && !p.confirmed => Some(Found::Block(block)),
            _ => None,
        }
    }

    /// The camera read `seen` with the robot at `robot`: remembered for each block.
    pub fn note_sightings(&mut self, seen: &[u32], robot: Point2) {
        for &id in seen {
            if matches!(
                MarkerCategory::of(id),
                MarkerCategory::RedBlock | MarkerCategory::BlueBlock
            ) {
                let odd = if id % 2 == 1 { id } else { id - 1 };
                self.seen_from.insert(odd, robot);
            }
        }
    }

    /// Where the robot was when the camera last read one of block `odd`'s markers: a
    /// marker is readable only from its own side, so an approach from there sees one.
    pub fn seen_from(&self, odd: u32) -> Option<Point2> {
        self.seen_from.get(&odd).copied()
    }

    /// Forgets a block (it was put down somewhere unknown): it is found again like a new one.
    pub fn forget(&mut self, odd: u32) {
        self.blocks.remove(&odd);
        self.seen_from.remove(&odd);
    }

    /// Marks a block delivered, its centre now `at`: it is no longer a target, wherever
    /// its markers turn up.
    pub fn deliver(&mut self, odd: u32, at: Point2) {
        if let Some(b) = self.blocks.get_mut(&odd) {
            b.delivered = true;
            b.position = at;
        }
    }

    /// Back to a potential block (seed 001 "Block Lost During Approach").
    pub fn demote(&mut self, odd: u32) {
        if let Some(b) = self.blocks.get_mut(&odd) {
            b.confirmed = false;
        }
    }

    pub fn blocks(&self) -> impl Iterator<Item = &Block> {
        self.blocks.values()
    }

    pub fn gates(&self) -> impl Iterator<Item = &Gate> {
        self.gates.values()
    }

    /// The gate a block of `colour` goes to, if one was found.
    pub fn gate_for(&self, colour: Colour) -> Option<&Gate> {
        self.gates.values().find(|g| g.colour == colour)
    }

    pub fn delivered(&self) -> usize {
        self.blocks.values().filter(|b| b.delivered).count()
    }
}

/// The centre of a square block of side `size` from the markers on two adjacent faces:
/// their midpoint lies size/4 * (u + v) from the centre, |u + v| = sqrt 2, on the side of
/// the pair the camera saw them from.
fn block_centre(a: Point2, b: Point2, robot: Point2, size: f64) -> Point2 {
    let mid = Point2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
    behind(mid, robot, size * std::f64::consts::SQRT_2 / 4.0)
}

/// The point `depth` metres beyond `p` as seen from `robot`.
fn behind(p: Point2, robot: Point2, depth: f64) -> Point2 {
    let d = p.distance(robot);
    if d < 1e-9 {
        return p;
    }
    Point2::new(
        p.x + depth * (p.x - robot.x) / d,
        p.y + depth * (p.y - robot.y) / d,
    )
}

/// A gate from its two markers: centre between them, normal towards the robot's side.
fn gate_from(
    colour: Colour,
    markers: [u32; 2],
    (a, b): (Point2, Point2),
    robot: Point2,
    map: &Costmap,
) -> Gate {
    let center = Point2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
    let normal = super::gate_side::gate_normal(map, a, b, robot);
    Gate {
        colour,
        markers,
        center,
        normal,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unknown() -> Costmap {
        Costmap::new(
            1,
            1,
            1.0,
            Point2::new(-50.0, -50.0),
            crate::map::costmap::NO_INFORMATION,
        )
    }

    fn map(entries: &[(u32, f64, f64)]) -> BTreeMap<u32, Point2> {
        entries
            .iter()
            .map(|&(id, x, y)| (id, Point2::new(x, y)))
            .collect()
    }

    #[test]
    fn one_marker_is_a_potential_block_two_confirm_it() {
        let mut o = Objects::default();
        let robot = Point2::new(0.0, 0.0);
        // A 0.05 m block at (1, 1), unturned: marker 421 on +x face, 422 on +y face.
        let one = map(&[(421, 1.025, 1.0)]);
        assert!(matches!(
            o.update(&one, robot, 0.05, &unknown())[..],
            [Found::PotentialBlock(_)]
        ));
        let both = map(&[(421, 1.025, 1.0), (422, 1.0, 1.025)]);
        let found = o.update(&both, Point2::new(2.0, 2.0), 0.05, &unknown());
        let [Found::Block(b)] = found[..] else {
            panic!("{found:?}")
        };
        assert!(b.position.distance(Point2::new(1.0, 1.0)) < 1e-9, "{b:?}");
        assert_eq!(b.colour, Colour::Red);
        // Seen again: nothing new to say.
        assert!(
            o.update(&both, Point2::new(2.0, 2.0), 0.05, &unknown())
                .is_empty()
        );
    }

    #[test]
    fn a_gate_faces_into_the_arena_and_a_delivered_block_stays_delivered() {
        let mut o = Objects::default();
        let marks = map(&[
            (401, 2.0, 1.15),
            (402, 2.0, 0.85),
            (423, 0.5, 0.0),
            (424, 0.5, 0.1),
        ]);
        let found = o.update(&marks, Point2::new(0.0, 0.0), 0.05, &unknown());
        assert_eq!(found.len(), 2);
        let gate = *o.gate_for(Colour::Red).unwrap();
        assert!((gate.normal.0 + 1.0).abs() < 1e-9, "{gate:?}");
        let drop = gate.in_front(0.3);
        assert!(drop.distance(Point2::new(1.7, 1.0)) < 1e-9);
        assert!(gate.facing().abs() < 1e-9, "faces +x, towards the wall");
        o.deliver(423, Point2::new(1.6, 1.0));
        assert_eq!(o.delivered(), 1);
        o.update(&marks, Point2::new(0.0, 0.0), 0.05, &unknown());
        assert!(o.blocks().all(|b| b.delivered));
        let moved = o.blocks().find(|b| b.markers[0] == 423).unwrap();
        assert_eq!(
            moved.position,
            Point2::new(1.6, 1.0),
            "drawn where it was put down"
        );
    }
}
