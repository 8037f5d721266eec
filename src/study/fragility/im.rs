//! The intensity measure of a record (m/s²): PGA, the 5 %-damped pseudo-spectral acceleration
//! at a period (the exact piecewise-linear oscillator of `pounding spectrum`,
//! [`spectral_point`]), or Sa_avg, the geometric mean of those over a set of periods
//! (Eads, Miranda & Lignos 2015, Earthquake Engng Struct. Dyn. 44(12)). All three scale
//! linearly with the record, so the factor to a stripe is level / IM.

use crate::analysis::record_spectrum::spectral_point;
use crate::input::fragility::IntensityMeasure;
use crate::model::ground_motion::Record;

/// The damping ratio of the spectral measures.
pub const DAMPING: f64 = 0.05;

/// The IM of `record` (as read, unscaled), m/s².
pub fn intensity(measure: &IntensityMeasure, record: &Record) -> f64 {
    let sa = |t: f64| spectral_point(&record.accel, record.dt, t, DAMPING).psa;
    match measure {
        IntensityMeasure::Pga => record.pga(),
        IntensityMeasure::Sa { period, .. } => sa(*period),
        IntensityMeasure::SaAvg { periods } => {
            let n = periods.len() as f64;
            (periods.iter().map(|&t| sa(t).ln()).sum::<f64>() / n).exp()
        }
    }
}
