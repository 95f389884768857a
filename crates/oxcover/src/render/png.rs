//! PNG output: the same scene rasterised with tiny-skia (anti-aliased path and
//! markers) and the public-domain 8×8 font of `font8x8`, doubled, for the legend.

use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform,
};

use super::{
    END_RGB, Layout, LegendMark, MARGIN_PX, MarkerShape, Overlay, PATH_RGB, PLANNED_RGB, START_RGB,
    Scene, Swatch, arrow_marks, legend_key, map_raster,
};
use crate::error::{Error, Result};

/// Renders the scene as PNG bytes.
///
/// # Errors
/// [`Error::Internal`] if the picture cannot be allocated or encoded.
pub fn render_png(scene: &Scene<'_>) -> Result<Vec<u8>> {
    let layout = Layout::of(scene);
    let mut pm = Pixmap::new(layout.width, layout.height)
        .ok_or_else(|| Error::Internal("cannot allocate the picture".into()))?;
    pm.fill(Color::WHITE);
    let raster = map_raster(scene, &layout);
    blit(&mut pm, MARGIN_PX, MARGIN_PX, layout.map_w, &raster);

    let stroke_w = (layout.scale * 0.3).clamp(1.0, 3.0) as f32;
    if let Some(planned) = scene.planned {
        let mut pb = PathBuilder::new();
        for (k, p) in planned.iter().enumerate() {
            let (x, y) = layout.pixel_of(scene.map, p);
            if k == 0 {
                pb.move_to(x as f32, y as f32);
            } else {
                pb.line_to(x as f32, y as f32);
            }
        }
        if let Some(path) = pb.finish() {
            let stroke = Stroke {
                width: (stroke_w * 0.6).max(1.0),
                line_join: LineJoin::Round,
                ..Stroke::default()
            };
            pm.stroke_path(
                &path,
                &paint(PLANNED_RGB),
                &stroke,
                Transform::identity(),
                None,
            );
        }
    }
    let px: Vec<(f64, f64)> = scene
        .path
        .iter()
        .map(|p| layout.pixel_of(scene.map, p))
        .collect();
    if px.len() >= 2 {
        let mut pb = PathBuilder::new();
        pb.move_to(px[0].0 as f32, px[0].1 as f32);
        for &(x, y) in &px[1..] {
            pb.line_to(x as f32, y as f32);
        }
        if let Some(path) = pb.finish() {
            let stroke = Stroke {
                width: stroke_w,
                line_cap: LineCap::Round,
                line_join: LineJoin::Round,
                ..Stroke::default()
            };
            pm.stroke_path(
                &path,
                &paint(PATH_RGB),
                &stroke,
                Transform::identity(),
                None,
            );
        }
        let size = (f64::from(stroke_w) * 3.0).max(5.0);
        let mut pb = PathBuilder::new();
        for (x, y, dx, dy) in arrow_marks(&px, 90.0) {
            let (bx, by) = (x - dx * size, y - dy * size);
            let (nx, ny) = (-dy * size * 0.6, dx * size * 0.6);
            pb.move_to(x as f32, y as f32);
            pb.line_to((bx + nx) as f32, (by + ny) as f32);
            pb.line_to((bx - nx) as f32, (by - ny) as f32);
            pb.close();
        }
        if let Some(path) = pb.finish() {
            pm.fill_path(
                &path,
                &paint(PATH_RGB),
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }
    if let Some(o) = scene.overlay {
        overlay(&mut pm, scene, &layout, o, stroke_w);
    }
    if let (Some(&(sx, sy)), Some(&(ex, ey))) = (px.first(), px.last()) {
        square(&mut pm, ex as f32, ey as f32, 6.0, END_RGB);
        disc(&mut pm, sx as f32, sy as f32, 7.0, START_RGB);
    }

    // Legend panel.
    let lx = layout.map_w + 2 * MARGIN_PX + 8;
    let mut y = MARGIN_PX + 8;
    text(&mut pm, lx, y, &scene.title, [0, 0, 0]);
    y += 30;
    for (label, sw) in legend_key(scene) {
        let (cx, cy) = (lx as f32 + 8.0, y as f32 + 8.0);
        match sw {
            Swatch::Cell(shade) => {
                rect(
                    &mut pm,
                    lx as f32 - 1.0,
                    y as f32 - 1.0,
                    18.0,
                    18.0,
                    [85, 85, 85],
                );
                rect(&mut pm, lx as f32, y as f32, 16.0, 16.0, shade.rgb());
            }
            Swatch::Line => rect(&mut pm, lx as f32, cy - 1.5, 16.0, 3.0, PATH_RGB),
            Swatch::Start => disc(&mut pm, cx, cy, 7.0, START_RGB),
            Swatch::End => square(&mut pm, cx, cy, 6.0, END_RGB),
        }
        text(&mut pm, lx + 26, y, label, [0, 0, 0]);
        y += 26;
    }
    for (label, rgb, mark) in scene.overlay.map(|o| o.legend.as_slice()).unwrap_or(&[]) {
        let (cx, cy) = (lx as f32 + 8.0, y as f32 + 8.0);
        match mark {
            LegendMark::Stroke => rect(&mut pm, lx as f32, cy - 1.5, 16.0, 3.0, *rgb),
            LegendMark::Line => rect(&mut pm, lx as f32, cy - 0.5, 16.0, 1.0, *rgb),
            LegendMark::Marker(shape) => marker(&mut pm, cx, cy, *rgb, *shape, 6.0),
        }
        text(&mut pm, lx + 26, y, label, [0, 0, 0]);
        y += 26;
    }
    y += 10;
    let right = layout.map_w + 2 * MARGIN_PX + layout.legend_w - 12;
    for (k, v) in &scene.rows {
        text(&mut pm, lx, y, k, [0, 0, 0]);
        let vw = super::CHAR_PX * v.chars().count() as u32;
        text(&mut pm, right.saturating_sub(vw), y, v, [0, 0, 0]);
        y += 26;
    }
    pm.encode_png()
        .map_err(|e| Error::Internal(format!("PNG encoding failed: {e}")))
}

/// The overlay's strokes, lines and markers.
fn overlay(pm: &mut Pixmap, scene: &Scene<'_>, layout: &Layout, o: &Overlay, stroke_w: f32) {
    let polyline = |pts: &[(f64, f64)]| {
        let mut pb = PathBuilder::new();
        for (k, &(x, y)) in pts.iter().enumerate() {
            if k == 0 {
                pb.move_to(x as f32, y as f32);
            } else {
                pb.line_to(x as f32, y as f32);
            }
        }
        pb.finish()
    };
    for (pts, rgb) in &o.strokes {
        let px: Vec<(f64, f64)> = pts.iter().map(|p| layout.pixel_of(scene.map, p)).collect();
        if let Some(path) = polyline(&px) {
            let stroke = Stroke {
                width: stroke_w,
                line_cap: LineCap::Round,
                line_join: LineJoin::Round,
                ..Stroke::default()
            };
            pm.stroke_path(&path, &paint(*rgb), &stroke, Transform::identity(), None);
        }
    }
    for (a, b, rgb) in &o.lines {
        let px = [layout.pixel_of(scene.map, a), layout.pixel_of(scene.map, b)];
        if let Some(path) = polyline(&px) {
            let stroke = Stroke {
                width: 1.5,
                ..Stroke::default()
            };
            pm.stroke_path(&path, &paint(*rgb), &stroke, Transform::identity(), None);
        }
    }
    for (p, rgb, shape, r) in &o.markers {
        let (x, y) = layout.pixel_of(scene.map, p);
        marker(pm, x as f32, y as f32, *rgb, *shape, *r as f32);
    }
    for (p, s, rgb) in &o.texts {
        let (x, y) = layout.pixel_of(scene.map, p);
        // Centred on the point: 16 px a glyph, 16 px tall.
        let (x, y) = (x.round() as i64 - 8 * s.len() as i64, y.round() as i64 - 8);
        for (dx, dy) in [
            (-2, 0),
            (2, 0),
            (0, -2),
            (0, 2),
            (-2, -2),
            (2, 2),
            (-2, 2),
            (2, -2),
        ] {
            glyphs(pm, x + dx, y + dy, s, [255, 255, 255]);
        }
        glyphs(pm, x, y, s, *rgb);
    }
}

fn marker(pm: &mut Pixmap, cx: f32, cy: f32, rgb: [u8; 3], shape: MarkerShape, r: f32) {
    match shape {
        MarkerShape::Disc => disc(pm, cx, cy, r, rgb),
        MarkerShape::Square => square(pm, cx, cy, r, rgb),
        MarkerShape::Ring => {
            if let Some(path) = PathBuilder::from_circle(cx, cy, r) {
                let stroke = Stroke {
                    width: 2.0,
                    ..Stroke::default()
                };
                pm.stroke_path(&path, &paint(rgb), &stroke, Transform::identity(), None);
            }
        }
    }
}

/// Encodes an RGB buffer as PNG (used for the SVG's embedded map).
pub(crate) fn encode_rgb(width: u32, height: u32, rgb: &[[u8; 3]]) -> Result<Vec<u8>> {
    let mut pm = Pixmap::new(width, height)
        .ok_or_else(|| Error::Internal("cannot allocate the map raster".into()))?;
    blit(&mut pm, 0, 0, width, rgb);
    pm.encode_png()
        .map_err(|e| Error::Internal(format!("PNG encoding failed: {e}")))
}

fn blit(pm: &mut Pixmap, x0: u32, y0: u32, w: u32, rgb: &[[u8; 3]]) {
    let pw = pm.width() as usize;
    let data = pm.data_mut();
    for (i, px) in rgb.iter().enumerate() {
        let (x, y) = (x0 as usize + i % w as usize, y0 as usize + i / w as usize);
        let o = (y * pw + x) * 4;
        if let Some(d) = data.get_mut(o..o + 4) {
            d.copy_from_slice(&[px[0], px[1], px[2], 255]);
        }
    }
}

fn paint(rgb: [u8; 3]) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color_rgba8(rgb[0], rgb[1], rgb[2], 255);
    p.anti_alias = true;
    p
}

fn rect(pm: &mut Pixmap, x: f32, y: f32, w: f32, h: f32, rgb: [u8; 3]) {
    if let Some(r) = Rect::from_xywh(x, y, w, h) {
        pm.fill_rect(r, &paint(rgb), Transform::identity(), None);
    }
}

fn square(pm: &mut Pixmap, cx: f32, cy: f32, half: f32, rgb: [u8; 3]) {
    rect(
        pm,
        cx - half - 1.0,
        cy - half - 1.0,
        2.0 * half + 2.0,
        2.0 * half + 2.0,
        [255, 255, 255],
    );
    rect(pm, cx - half, cy - half, 2.0 * half, 2.0 * half, rgb);
}

fn disc(pm: &mut Pixmap, cx: f32, cy: f32, r: f32, rgb: [u8; 3]) {
    for (rad, colour) in [(r + 1.0, [255, 255, 255]), (r, rgb)] {
        if let Some(path) = PathBuilder::from_circle(cx, cy, rad) {
            pm.fill_path(
                &path,
                &paint(colour),
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }
}

/// Draws ASCII text with the 8×8 font at twice its size (16 px per glyph).
fn text(pm: &mut Pixmap, x: u32, y: u32, s: &str, rgb: [u8; 3]) {
    glyphs(pm, i64::from(x), i64::from(y), s, rgb);
}

/// [`text`] with its top left corner at `(x, y)`, which may lie off the
/// picture (what does is cut).
fn glyphs(pm: &mut Pixmap, x: i64, y: i64, s: &str, rgb: [u8; 3]) {
    const SCALE: i64 = 2;
    let (pw, ph) = (i64::from(pm.width()), i64::from(pm.height()));
    let data = pm.data_mut();
    for (i, ch) in s.chars().enumerate() {
        let code = if ch.is_ascii() {
            ch as usize
        } else {
            b'?' as usize
        };
        let glyph = font8x8::legacy::BASIC_LEGACY[code];
        let gx = x + i as i64 * 8 * SCALE;
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8i64 {
                if bits & (1 << col) == 0 {
                    continue;
                }
                for dy in 0..SCALE {
                    for dx in 0..SCALE {
                        let (px, py) = (gx + col * SCALE + dx, y + row as i64 * SCALE + dy);
                        if (0..pw).contains(&px) && (0..ph).contains(&py) {
                            let o = ((py * pw + px) * 4) as usize;
                            data[o..o + 4].copy_from_slice(&[rgb[0], rgb[1], rgb[2], 255]);
                        }
                    }
                }
            }
        }
    }
}
