//! TEMPORARY stub until the plotting module lands.
use std::path::{Path, PathBuf};
/// err
#[derive(Debug, thiserror::Error)]
#[error("plot")]
pub struct PlotError;
/// style
#[derive(Clone, Copy)]
pub enum LineStyle {
    Solid,
    Dashed,
}
/// series
pub struct Series<'a> {
    pub label: &'a str,
    pub x: &'a [f64],
    pub y: &'a [f64],
    pub style: LineStyle,
}
/// panel
pub struct Panel<'a> {
    pub title: &'a str,
    pub y_label: &'a str,
    pub series: Vec<Series<'a>>,
}
/// fig
pub struct Figure<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub panels: Vec<Panel<'a>>,
    pub width: u32,
    pub height: u32,
}
/// write
pub fn write_figure(_f: &Figure, _s: &Path) -> Result<Vec<PathBuf>, PlotError> {
    Ok(vec![])
}
