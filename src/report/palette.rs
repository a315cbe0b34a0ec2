//! Colours of the pictures and legends. A surface's colour is a function of its name alone (a hue
//! from the blake3 hash of the name), so a horizon keeps its colour when other surfaces are added
//! to the recipe; box sides are grey. Regions are coloured by their id (index) from a fixed
//! palette of well-separated colours. Shading multiplies a colour by a quantised light level, so
//! the pictures need only a few CSS classes per colour.

use geom::mesh::SurfaceKind;

/// An sRGB colour.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl Rgb {
    /// `#rrggbb`.
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }

    /// The colour scaled by `k` in [0, 1].
    pub fn shade(self, k: f64) -> Rgb {
        let k = k.clamp(0.0, 1.0);
        let s = |c: u8| (c as f64 * k).round().clamp(0.0, 255.0) as u8;
        Rgb(s(self.0), s(self.1), s(self.2))
    }
}

/// Qualitative palette for regions (index order), after the common 12-class paired schemes.
const REGIONS: [Rgb; 12] = [
    Rgb(0x4e, 0x79, 0xa7),
    Rgb(0xf2, 0x8e, 0x2b),
    Rgb(0xe1, 0x57, 0x59),
    Rgb(0x76, 0xb7, 0xb2),
    Rgb(0x59, 0xa1, 0x4f),
    Rgb(0xed, 0xc9, 0x48),
    Rgb(0xb0, 0x7a, 0xa1),
    Rgb(0xff, 0x9d, 0xa7),
    Rgb(0x9c, 0x75, 0x5f),
    Rgb(0xba, 0xb0, 0xac),
    Rgb(0x3b, 0x4c, 0xc0),
    Rgb(0x8c, 0xd1, 0x7d),
];

/// The colour of region `i`; after the twelfth the palette repeats, darker.
pub fn region(i: usize) -> Rgb {
    let base = REGIONS[i % REGIONS.len()];
    let round = (i / REGIONS.len()) as i32;
    base.shade(0.8f64.powi(round.min(4)))
}

/// The colour of a surface, from its name and kind.
pub fn surface(name: &str, kind: SurfaceKind) -> Rgb {
    if kind == SurfaceKind::Box {
        return Rgb(0xb8, 0xb8, 0xb8);
    }
    let h = blake3::hash(name.as_bytes());
    let b = h.as_bytes();
    let hue = u16::from_le_bytes([b[0], b[1]]) as f64 / 65536.0 * 360.0;
    // Faults a little darker and more saturated than horizons, so they read as faults.
    let (s, l) = match kind {
        SurfaceKind::Fault => (0.75, 0.45),
        _ => (0.55, 0.6),
    };
    hsl(hue, s, l)
}

/// HSL (hue in degrees) to sRGB.
fn hsl(h: f64, s: f64, l: f64) -> Rgb {
    let c = (1.0 - (2.0 * l - 1.0).abs()) * s;
    let hp = (h.rem_euclid(360.0)) / 60.0;
    let x = c * (1.0 - (hp.rem_euclid(2.0) - 1.0).abs());
    let (r, g, b) = match hp as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = l - c / 2.0;
    let q = |v: f64| ((v + m) * 255.0).round().clamp(0.0, 255.0) as u8;
    Rgb(q(r), q(g), q(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_surface_colour_depends_only_on_its_name_and_kind() {
        let a = surface("H1", SurfaceKind::Horizon);
        assert_eq!(a, surface("H1", SurfaceKind::Horizon));
        assert_ne!(a, surface("H2", SurfaceKind::Horizon));
        assert_eq!(surface("box.top", SurfaceKind::Box).hex(), "#b8b8b8");
    }

    #[test]
    fn hsl_primaries_convert_exactly() {
        assert_eq!(hsl(0.0, 1.0, 0.5), Rgb(255, 0, 0));
        assert_eq!(hsl(120.0, 1.0, 0.5), Rgb(0, 255, 0));
        assert_eq!(hsl(240.0, 1.0, 0.5), Rgb(0, 0, 255));
    }

    #[test]
    fn region_colours_differ_within_a_palette_round() {
        for i in 0..12 {
            for j in 0..i {
                assert_ne!(region(i), region(j));
            }
        }
        assert_ne!(region(0), region(12));
    }
}
