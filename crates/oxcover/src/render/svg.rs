//! SVG output: the map as an embedded PNG (pixelated), the path and markers as
//! vectors, the legend as text.

use std::fmt::Write as _;

use super::{
    END_RGB, Layout, LegendMark, MARGIN_PX, MarkerShape, Overlay, PATH_RGB, PLANNED_RGB, START_RGB,
    Scene, Swatch, arrow_marks, legend_key, map_raster,
};
use crate::error::Result;

/// Renders the scene as an SVG document.
///
/// # Errors
/// [`crate::Error::Internal`] if the embedded raster cannot be encoded.
pub fn render_svg(scene: &Scene<'_>) -> Result<String> {
    let layout = Layout::of(scene);
    let raster = map_raster(scene, &layout);
    let png = super::png::encode_rgb(layout.map_w, layout.map_h, &raster)?;
    let mut s = String::with_capacity(png.len() * 4 / 3 + scene.path.len() * 16 + 4096);
    let (w, h) = (layout.width, layout.height);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<image x="{m}" y="{m}" width="{mw}" height="{mh}" style="image-rendering:pixelated" href="data:image/png;base64,{data}"/>"#,
        m = MARGIN_PX,
        mw = layout.map_w,
        mh = layout.map_h,
        data = base64(&png)
    );
    let stroke = (layout.scale * 0.3).clamp(1.0, 3.0);
    if let Some(planned) = scene.planned.filter(|p| p.len() >= 2) {
        let _ = write!(
            s,
            r#"<polyline fill="none" stroke-linejoin="round" stroke="{}" stroke-width="{:.2}" points=""#,
            hex(PLANNED_RGB),
            (stroke * 0.6).max(1.0)
        );
        for p in planned {
            let (x, y) = layout.pixel_of(scene.map, p);
            let _ = write!(s, "{x:.2},{y:.2} ");
        }
        s.push_str("\"/>\n");
    }
    let px: Vec<(f64, f64)> = scene
        .path
        .iter()
        .map(|p| layout.pixel_of(scene.map, p))
        .collect();
    if px.len() >= 2 {
        s.push_str(r#"<polyline fill="none" stroke-linejoin="round" stroke-linecap="round""#);
        let _ = write!(
            s,
            r#" stroke="{}" stroke-width="{stroke:.2}" points=""#,
            hex(PATH_RGB)
        );
        for (x, y) in &px {
            let _ = write!(s, "{x:.2},{y:.2} ");
        }
        s.push_str("\"/>\n");
        let size = (stroke * 3.0).max(5.0);
        s.push_str(r#"<path fill=""#);
        s.push_str(&hex(PATH_RGB));
        s.push_str(r#"" d=""#);
        for (x, y, dx, dy) in arrow_marks(&px, 90.0) {
            let (bx, by) = (x - dx * size, y - dy * size);
            let (nx, ny) = (-dy * size * 0.6, dx * size * 0.6);
            let _ = write!(
                s,
                "M{x:.2},{y:.2}L{:.2},{:.2}L{:.2},{:.2}Z",
                bx + nx,
                by + ny,
                bx - nx,
                by - ny
            );
        }
        s.push_str("\"/>\n");
    }
    if let Some(o) = scene.overlay {
        overlay(&mut s, scene, &layout, o, stroke);
    }
    if let (Some(&(sx, sy)), Some(&(ex, ey))) = (px.first(), px.last()) {
        let _ = writeln!(
            s,
            r#"<rect x="{:.2}" y="{:.2}" width="12" height="12" fill="{}" stroke="white"/>"#,
            ex - 6.0,
            ey - 6.0,
            hex(END_RGB)
        );
        let _ = writeln!(
            s,
            r#"<circle cx="{sx:.2}" cy="{sy:.2}" r="7" fill="{}" stroke="white"/>"#,
            hex(START_RGB)
        );
    }
    // Legend panel.
    let lx = layout.map_w + 2 * MARGIN_PX;
    let _ = writeln!(
        s,
        r#"<g font-family="DejaVu Sans Mono, Menlo, Consolas, monospace" font-size="15" fill="black">"#
    );
    let mut y = MARGIN_PX + 20;
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{y}" font-weight="bold">{}</text>"#,
        lx + 8,
        escape(&scene.title)
    );
    y += 30;
    for (label, sw) in legend_key(scene) {
        let (x0, y0) = (lx + 8, y - 12);
        match sw {
            Swatch::Cell(shade) => {
                let _ = writeln!(
                    s,
                    r##"<rect x="{x0}" y="{y0}" width="16" height="14" fill="{}" stroke="#555"/>"##,
                    shade.hex()
                );
            }
            Swatch::Line => {
                let _ = writeln!(
                    s,
                    r#"<line x1="{x0}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="3"/>"#,
                    y0 + 7,
                    x0 + 16,
                    y0 + 7,
                    hex(PATH_RGB)
                );
            }
            Swatch::Start => {
                let _ = writeln!(
                    s,
                    r#"<circle cx="{}" cy="{}" r="7" fill="{}"/>"#,
                    x0 + 8,
                    y0 + 7,
                    hex(START_RGB)
                );
            }
            Swatch::End => {
                let _ = writeln!(
                    s,
                    r#"<rect x="{}" y="{y0}" width="12" height="12" fill="{}"/>"#,
                    x0 + 2,
                    hex(END_RGB)
                );
            }
        }
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{y}">{}</text>"#,
            x0 + 26,
            escape(label)
        );
        y += 26;
    }
    for (label, rgb, mark) in scene.overlay.map(|o| o.legend.as_slice()).unwrap_or(&[]) {
        let (x0, y0) = (lx + 8, y - 12);
        let c = hex(*rgb);
        match mark {
            LegendMark::Stroke | LegendMark::Line => {
                let w = if *mark == LegendMark::Stroke { 3 } else { 1 };
                let _ = writeln!(
                    s,
                    r#"<line x1="{x0}" y1="{}" x2="{}" y2="{}" stroke="{c}" stroke-width="{w}"/>"#,
                    y0 + 7,
                    x0 + 16,
                    y0 + 7
                );
            }
            LegendMark::Marker(shape) => marker(
                &mut s,
                f64::from(x0 + 8),
                f64::from(y0 + 7),
                *rgb,
                *shape,
                6.0,
            ),
        }
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{y}">{}</text>"#,
            x0 + 26,
            escape(label)
        );
        y += 26;
    }
    y += 10;
    for (k, v) in &scene.rows {
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{y}">{}</text><text x="{}" y="{y}" text-anchor="end">{}</text>"#,
            lx + 8,
            escape(k),
            lx + layout.legend_w - 12,
            escape(v)
        );
        y += 26;
    }
    s.push_str("</g>\n</svg>\n");
    Ok(s)
}

/// The overlay's strokes, lines and markers.
fn overlay(s: &mut String, scene: &Scene<'_>, layout: &Layout, o: &Overlay, stroke: f64) {
    for (pts, rgb) in &o.strokes {
        if pts.len() < 2 {
            continue;
        }
        let _ = write!(
            s,
            r#"<polyline fill="none" stroke-linejoin="round" stroke-linecap="round" stroke="{}" stroke-width="{stroke:.2}" points=""#,
            hex(*rgb)
        );
        for p in pts {
            let (x, y) = layout.pixel_of(scene.map, p);
            let _ = write!(s, "{x:.2},{y:.2} ");
        }
        s.push_str("\"/>\n");
    }
    for (a, b, rgb) in &o.lines {
        let ((x1, y1), (x2, y2)) = (layout.pixel_of(scene.map, a), layout.pixel_of(scene.map, b));
        let _ = writeln!(
            s,
            r#"<line x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}" stroke="{}" stroke-width="1.5"/>"#,
            hex(*rgb)
        );
    }
    for (p, rgb, shape, r) in &o.markers {
        let (x, y) = layout.pixel_of(scene.map, p);
        marker(s, x, y, *rgb, *shape, *r);
    }
    for (p, t, rgb) in &o.texts {
        let (x, y) = layout.pixel_of(scene.map, p);
        let _ = writeln!(
            s,
            r#"<text x="{x:.2}" y="{y:.2}" text-anchor="middle" dominant-baseline="central" font-family="DejaVu Sans Mono, Menlo, Consolas, monospace" font-size="16" font-weight="bold" fill="{}" stroke="white" stroke-width="4" paint-order="stroke">{}</text>"#,
            hex(*rgb),
            escape(t)
        );
    }
}

fn marker(s: &mut String, x: f64, y: f64, rgb: [u8; 3], shape: MarkerShape, r: f64) {
    let c = hex(rgb);
    let _ = match shape {
        MarkerShape::Disc => writeln!(
            s,
            r#"<circle cx="{x:.2}" cy="{y:.2}" r="{r:.1}" fill="{c}" stroke="white"/>"#
        ),
        MarkerShape::Ring => writeln!(
            s,
            r#"<circle cx="{x:.2}" cy="{y:.2}" r="{r:.1}" fill="none" stroke="{c}" stroke-width="2"/>"#
        ),
        MarkerShape::Square => writeln!(
            s,
            r#"<rect x="{:.2}" y="{:.2}" width="{:.1}" height="{:.1}" fill="{c}" stroke="white"/>"#,
            x - r,
            y - r,
            2.0 * r,
            2.0 * r
        ),
    };
}

fn hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

fn escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Standard base64 with padding (RFC 4648).
fn base64(data: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(data.len().div_ceil(3) * 4);
    for chunk in data.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        out.push(A[(n >> 18) as usize & 63] as char);
        out.push(A[(n >> 12) as usize & 63] as char);
        out.push(if chunk.len() > 1 {
            A[(n >> 6) as usize & 63] as char
        } else {
            '='
        });
        out.push(if chunk.len() > 2 {
            A[n as usize & 63] as char
        } else {
            '='
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        for (i, o) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(i.as_bytes()), o);
        }
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
