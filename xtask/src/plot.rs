//! Small SVG line charts for the reproduction pages: lines, shaded bands,
//! axes with round ticks, a legend. Deterministic text output.

use std::fmt::Write as _;

/// A line.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend label.
    pub name: String,
    /// CSS colour.
    pub colour: &'static str,
    /// `(x, y)` points, drawn in order.
    pub points: Vec<(f64, f64)>,
    /// Dashed line.
    pub dashed: bool,
}

/// A shaded band between two lines sharing their x values.
#[derive(Clone, Debug)]
pub struct Band {
    /// Legend label.
    pub name: String,
    /// CSS colour.
    pub colour: &'static str,
    /// `(x, low, high)` points.
    pub points: Vec<(f64, f64, f64)>,
}

/// A chart.
#[derive(Clone, Debug)]
pub struct Chart {
    /// Title above the plot.
    pub title: String,
    /// X axis label.
    pub x_label: String,
    /// Y axis label.
    pub y_label: String,
    /// Bands (drawn first).
    pub bands: Vec<Band>,
    /// Lines.
    pub series: Vec<Series>,
}

fn nice_step(span: f64) -> f64 {
    let raw = span / 6.0;
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let nice = if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

impl Chart {
    /// The chart as an SVG document (720 × 420 px).
    #[must_use]
    pub fn svg(&self) -> String {
        let (w, h) = (720.0, 420.0);
        let (l, r, t, b) = (70.0, 180.0, 40.0, 50.0);
        let xs = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.0))
            .chain(self.bands.iter().flat_map(|b| b.points.iter().map(|p| p.0)));
        let ys = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .chain(
                self.bands
                    .iter()
                    .flat_map(|b| b.points.iter().flat_map(|p| [p.1, p.2])),
            );
        let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
        for x in xs {
            x0 = x0.min(x);
            x1 = x1.max(x);
        }
        let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
        for y in ys {
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        if !x0.is_finite() {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
        }
        if x1 <= x0 {
            x1 = x0 + 1.0;
        }
        let ystep = nice_step((y1 - y0).max(1e-9));
        y0 = (y0 / ystep).floor() * ystep;
        y1 = (y1 / ystep).ceil() * ystep;
        if y1 <= y0 {
            y1 = y0 + ystep;
        }
        let px = |x: f64| l + (x - x0) / (x1 - x0) * (w - l - r);
        let py = |y: f64| h - b - (y - y0) / (y1 - y0) * (h - t - b);
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans, Helvetica, Arial, sans-serif" font-size="12">"#
        );
        let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="22" font-size="15" font-weight="bold">{}</text>"#,
            l,
            esc(&self.title)
        );
        // Axes and ticks.
        let mut y = y0;
        while y <= y1 + ystep * 1e-6 {
            let _ = writeln!(
                s,
                r##"<line x1="{l}" x2="{}" y1="{:.1}" y2="{:.1}" stroke="#e5e5e5"/><text x="{}" y="{:.1}" text-anchor="end">{}</text>"##,
                w - r,
                py(y),
                py(y),
                l - 6.0,
                py(y) + 4.0,
                fmt_tick(y)
            );
            y += ystep;
        }
        let xstep = nice_step(x1 - x0);
        let mut x = (x0 / xstep).ceil() * xstep;
        while x <= x1 + xstep * 1e-6 {
            let _ = writeln!(
                s,
                r#"<text x="{:.1}" y="{}" text-anchor="middle">{}</text>"#,
                px(x),
                h - b + 16.0,
                fmt_tick(x)
            );
            x += xstep;
        }
        let _ = writeln!(
            s,
            r#"<line x1="{l}" x2="{l}" y1="{t}" y2="{}" stroke="black"/><line x1="{l}" x2="{}" y1="{}" y2="{}" stroke="black"/>"#,
            h - b,
            w - r,
            h - b,
            h - b
        );
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
            (l + w - r) / 2.0,
            h - 10.0,
            esc(&self.x_label)
        );
        let _ = writeln!(
            s,
            r#"<text transform="translate(18 {}) rotate(-90)" text-anchor="middle">{}</text>"#,
            (t + h - b) / 2.0,
            esc(&self.y_label)
        );
        // Bands, then lines.
        for band in &self.bands {
            let mut d = String::new();
            for (i, p) in band.points.iter().enumerate() {
                let _ = write!(
                    d,
                    "{}{:.1},{:.1}",
                    if i == 0 { "M" } else { "L" },
                    px(p.0),
                    py(p.2)
                );
            }
            for p in band.points.iter().rev() {
                let _ = write!(d, "L{:.1},{:.1}", px(p.0), py(p.1));
            }
            let _ = writeln!(
                s,
                r#"<path d="{d}Z" fill="{}" fill-opacity="0.35" stroke="none"/>"#,
                band.colour
            );
        }
        for line in &self.series {
            let pts: Vec<String> = line
                .points
                .iter()
                .map(|p| format!("{:.1},{:.1}", px(p.0), py(p.1)))
                .collect();
            let dash = if line.dashed {
                r#" stroke-dasharray="6 4""#
            } else {
                ""
            };
            let _ = writeln!(
                s,
                r#"<polyline fill="none" stroke="{}" stroke-width="1.8"{dash} points="{}"/>"#,
                line.colour,
                pts.join(" ")
            );
        }
        // Legend.
        let mut ly = t + 10.0;
        let lx = w - r + 16.0;
        for band in &self.bands {
            let _ = writeln!(
                s,
                r#"<rect x="{lx}" y="{}" width="18" height="10" fill="{}" fill-opacity="0.35"/><text x="{}" y="{}">{}</text>"#,
                ly - 8.0,
                band.colour,
                lx + 24.0,
                ly + 1.0,
                esc(&band.name)
            );
            ly += 20.0;
        }
        for line in &self.series {
            let dash = if line.dashed {
                r#" stroke-dasharray="6 4""#
            } else {
                ""
            };
            let _ = writeln!(
                s,
                r#"<line x1="{lx}" x2="{}" y1="{}" y2="{}" stroke="{}" stroke-width="2"{dash}/><text x="{}" y="{}">{}</text>"#,
                lx + 18.0,
                ly - 3.0,
                ly - 3.0,
                line.colour,
                lx + 24.0,
                ly + 1.0,
                esc(&line.name)
            );
            ly += 20.0;
        }
        s.push_str("</svg>\n");
        s
    }
}

fn fmt_tick(v: f64) -> String {
    if (v - v.round()).abs() < 1e-9 {
        format!("{}", v.round() as i64)
    } else {
        format!("{v:.2}")
    }
}

fn esc(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
