//! Which stations' time histories a run streams to its floor sink (`[output]
//! floor_stations`, the columns of `floors.csv`).

/// Which stations' time histories `floors.csv` holds (`[output] floor_stations`); the peaks
/// over the height (summary.json, envelopes.png) always cover every station.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FloorStations {
    /// Every floor of a building with floors; of a cantilever, the stations at the contact
    /// heights and at the top (`"contact"`, the default: the histories an engineer reads;
    /// a cantilever's 10 tenths of its height would make floors.csv 5–10× larger).
    #[default]
    Contact,
    /// Every station, a cantilever's every tenth of its height too (`"all"`).
    All,
}

impl FloorStations {
    /// The names `[output] floor_stations` accepts, in the order of [`FloorStations::ALL`].
    pub const NAMES: [&'static str; 2] = ["contact", "all"];
    /// Every choice.
    pub const ALL: [FloorStations; 2] = [FloorStations::Contact, FloorStations::All];

    /// The choice of a name of [`FloorStations::NAMES`].
    pub fn from_name(name: &str) -> Option<FloorStations> {
        Self::NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| Self::ALL[i])
    }

    /// Indices of the values of a floor row of `floors`
    /// ([`crate::recording::floor_response::FloorRecorder::columns`]) that `floors.csv` keeps for a
    /// system whose structures are `system` and whose contact heights are `heights` (m);
    /// `None`: every value.
    pub fn selection(
        self,
        system: &crate::model::system::System,
        floors: &crate::recording::floor_response::FloorRecorder,
        heights: &[f64],
    ) -> Option<Vec<usize>> {
        if self == FloorStations::All {
            return None;
        }
        let mut keep = Vec::new();
        let mut offset = 0;
        let mut all = true;
        for (m, st) in system.structures.iter().zip(floors.station_heights()) {
            let cantilever = matches!(m.shapes, crate::model::modal::Shapes::Cantilever(_));
            // (the stations include the contact heights and the top exactly, up to the
            // 1e-9·L within which they were merged with a tenth of the height)
            let tol = 1e-9 * m.length;
            for (j, &x) in st.iter().enumerate() {
                let wanted = !cantilever
                    || (x - m.length).abs() <= tol
                    || heights.iter().any(|&h| (x - h).abs() <= tol);
                if wanted {
                    keep.extend([offset + 2 * j, offset + 2 * j + 1]);
                } else {
                    all = false;
                }
            }
            offset += 2 * st.len();
        }
        (!all).then_some(keep)
    }
}
