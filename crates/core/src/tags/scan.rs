//! The scan list (seed 003 §1.2.3 `get_excel_scan_waypoints`, §2.2 mode 4), read from
//! CSV rather than Excel: the `group_id` column, runs of one id merged
//! (`[4, 4, 4, 5, 5, 6]` -> `[4, 5, 6]`), each group's tag `100 + group_id`, and a route
//! from the dock through them in order and back (`508 -> 104 -> 105 -> 106 -> 508`).

use super::file::{TagId, TagMap};
use super::graph::{Blocked, Route, RouteError};

/// seed 003 §2.2: tag id = 100 + group id.
pub const GROUP_TAG_BASE: TagId = 100;

/// The tags to scan and the route that visits them.
#[derive(Clone, Debug, PartialEq)]
pub struct ScanRoute {
    /// The groups' tags, runs merged, in the list's order.
    pub scan_tags: Vec<TagId>,
    /// Dock, the scan tags, dock.
    pub waypoints: Vec<TagId>,
    pub route: Route,
}

/// A scan list refused, naming the row (1-based, the header being row 1) where there is
/// one.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ScanError {
    #[error("{0}")]
    Csv(String),
    #[error("no group_id column (columns: {})", columns.join(", "))]
    NoGroupColumn { columns: Vec<String> },
    #[error("row {row}: group_id {value:?} is not a whole number")]
    BadGroup { row: usize, value: String },
    #[error("row {row}: group {group} is tag {tag}, which the map lacks")]
    NoTag { row: usize, group: u32, tag: TagId },
    #[error("the list names no group")]
    Empty,
    #[error("{0}")]
    Route(RouteError),
}

/// The scan route for the CSV `text` on `map`.
pub fn route_from_scan(map: &TagMap, text: &str) -> Result<ScanRoute, ScanError> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(text.as_bytes());
    let headers = reader
        .headers()
        .map_err(|e| ScanError::Csv(e.to_string()))?
        .clone();
    let column = headers
        .iter()
        .position(|h| h.eq_ignore_ascii_case("group_id"))
        .ok_or_else(|| ScanError::NoGroupColumn {
            columns: headers.iter().map(str::to_string).collect(),
        })?;
    let mut scan_tags: Vec<TagId> = Vec::new();
    for (i, record) in reader.records().enumerate() {
        let row = i + 2;
        let record = record.map_err(|e| ScanError::Csv(e.to_string()))?;
        let value = record.get(column).unwrap_or("");
        if value.is_empty() {
            continue;
        }
        // Spreadsheets write whole numbers as "4.0".
        let group = value
            .parse::<u32>()
            .ok()
            .or_else(|| {
                let f = value.parse::<f64>().ok()?;
                (f.fract() == 0.0 && (0.0..1e6).contains(&f)).then_some(f as u32)
            })
            .ok_or_else(|| ScanError::BadGroup {
                row,
                value: value.to_string(),
            })?;
        let tag = GROUP_TAG_BASE + group;
        if !map.tags.contains_key(&tag) {
            return Err(ScanError::NoTag { row, group, tag });
        }
        if scan_tags.last() != Some(&tag) {
            scan_tags.push(tag);
        }
    }
    if scan_tags.is_empty() {
        return Err(ScanError::Empty);
    }
    let mut waypoints = vec![map.dock];
    waypoints.extend(&scan_tags);
    waypoints.push(map.dock);
    let route = map
        .route(&waypoints, &Blocked::new())
        .map_err(ScanError::Route)?;
    Ok(ScanRoute {
        scan_tags,
        waypoints,
        route,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dock 508 and tags 104-106 in a line, edges both ways.
    const LINE: &str = "
tags:
  508: {x: 0, y: 0, type: dock, zone: DOCK}
  104: {x: 1, y: 0, type: shelf, zone: A}
  105: {x: 2, y: 0, type: shelf, zone: A}
  106: {x: 3, y: 0, type: shelf, zone: A}
edges:
  508: [{to: 104, direction: forward, type: straight}]
  104: [{to: 105, direction: forward, type: straight}, {to: 508, direction: backward, type: straight}]
  105: [{to: 106, direction: forward, type: straight}, {to: 104, direction: backward, type: straight}]
  106: [{to: 105, direction: backward, type: straight}]
";

    fn line() -> TagMap {
        TagMap::parse(LINE).unwrap()
    }

    #[test]
    fn runs_of_a_group_merge_and_the_route_goes_from_the_dock_and_back() {
        let csv = "item,group_id\na,4\nb,4\nc,4\nd,5\ne,5.0\nf,6\n";
        let r = route_from_scan(&line(), csv).unwrap();
        assert_eq!(r.scan_tags, vec![104, 105, 106]);
        assert_eq!(r.waypoints, vec![508, 104, 105, 106, 508]);
        assert_eq!(r.route.tags, vec![508, 104, 105, 106, 105, 104, 508]);
    }

    #[test]
    fn a_bad_list_names_its_row_or_its_columns() {
        let m = line();
        assert_eq!(
            route_from_scan(&m, "item,group_id\na,4\nb,four\n"),
            Err(ScanError::BadGroup {
                row: 3,
                value: "four".into()
            })
        );
        assert_eq!(
            route_from_scan(&m, "item,group_id\na,9\n"),
            Err(ScanError::NoTag {
                row: 2,
                group: 9,
                tag: 109
            })
        );
        let e = route_from_scan(&m, "item,group\na,4\n").unwrap_err();
        assert_eq!(e.to_string(), "no group_id column (columns: item, group)");
        assert_eq!(route_from_scan(&m, "group_id\n"), Err(ScanError::Empty));
    }
}
