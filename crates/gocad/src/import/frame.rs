//! How an object's coordinates map into the recipe's frame: each axis scaled from its `AXIS_UNIT`
//! (metres when the object has no coordinate-system block) into the target units, and z negated
//! under `ZPOSITIVE Depth`. Every object type the importer reads goes through it, so the objects
//! of one recipe land in one frame whatever their type.

use super::parser::GocadObject;
use super::{ImportError, Units};

/// The transform of one object.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame {
    scale: [f64; 3],
    zsign: f64,
}

impl Frame {
    /// The object's transform; an unknown AXIS_UNIT or ZPOSITIVE is an error naming its line.
    pub(super) fn of(
        o: &GocadObject,
        label: &str,
        target: Option<Units>,
    ) -> Result<Frame, ImportError> {
        let scale = axis_scale(o, label, target)?;
        let zsign = if z_is_depth(o, label)? { -1.0 } else { 1.0 };
        Ok(Frame { scale, zsign })
    }

    /// `p` in the recipe's frame, `None` when a coordinate overflows.
    pub(super) fn apply(&self, p: [f64; 3]) -> Option<[f64; 3]> {
        let s = self.scale;
        let q = [p[0] * s[0], p[1] * s[1], self.zsign * p[2] * s[2]];
        q.iter().all(|c| c.is_finite()).then_some(q)
    }

    /// Moves `points` into the frame; `lines[i]` is the line the overflow error names for point i.
    pub(super) fn place_all(
        &self,
        points: &mut [[f64; 3]],
        lines: &[u32],
        label: &str,
    ) -> Result<(), ImportError> {
        for (i, p) in points.iter_mut().enumerate() {
            let line = lines.get(i).copied().unwrap_or(0) as usize;
            *p = self.place(*p, line, label)?;
        }
        Ok(())
    }

    /// `p` in the frame, or the overflow error naming `line`.
    pub(super) fn place(
        &self,
        p: [f64; 3],
        line: usize,
        label: &str,
    ) -> Result<[f64; 3], ImportError> {
        self.apply(p)
            .ok_or_else(|| ImportError::new(label, line, "coordinate overflows after unit scaling"))
    }

    /// The z axis scale (the unit of measured depths when a Well does not name one).
    pub(super) fn z_scale(&self) -> f64 {
        self.scale[2]
    }
}

/// Scale from a unit as written into the target units; `what` names the record in the error.
pub(super) fn unit_scale(
    unit: &str,
    what: &str,
    line: usize,
    label: &str,
    target: Option<Units>,
) -> Result<f64, ImportError> {
    let Some(target) = target else {
        return Ok(1.0);
    };
    let u = Units::parse(unit).ok_or_else(|| {
        ImportError::new(
            label,
            line,
            format!("{what} '{unit}' is not a length unit this importer knows (m, km, ft)"),
        )
    })?;
    Ok(u.metres() / target.metres())
}

/// Per-axis scale from the object's AXIS_UNIT into the target units.
fn axis_scale(
    o: &GocadObject,
    label: &str,
    target: Option<Units>,
) -> Result<[f64; 3], ImportError> {
    let Some(target) = target else {
        return Ok([1.0; 3]);
    };
    let Some((units, line)) = &o.crs.axis_units else {
        return Ok([Units::Metre.metres() / target.metres(); 3]);
    };
    let mut s = [1.0; 3];
    for k in 0..3 {
        s[k] = unit_scale(&units[k], "AXIS_UNIT", *line, label, Some(target))?;
    }
    Ok(s)
}

fn z_is_depth(o: &GocadObject, label: &str) -> Result<bool, ImportError> {
    match &o.crs.zpositive {
        None => Ok(false),
        Some((v, line)) => match v.to_ascii_lowercase().as_str() {
            "depth" => Ok(true),
            "elevation" => Ok(false),
            _ => Err(ImportError::new(
                label,
                *line,
                format!("ZPOSITIVE must be Elevation or Depth, found '{v}'"),
            )),
        },
    }
}
