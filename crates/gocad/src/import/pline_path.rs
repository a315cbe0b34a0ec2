//! A PLine read as one open path (a well trajectory drawn as a line): its segments must chain
//! end to end without branching, closing or breaking, and the path starts at its higher end, as
//! a well starts at its head.

use super::ImportError;
use super::pline::Polyline;

impl Polyline {
    /// The vertices of the line in path order from its higher end (ties: the end read first),
    /// with the line of each one's record. Fails, naming the file and line, on a segment from a
    /// vertex to itself, a vertex where the line branches, a closed line, or a line in several
    /// pieces.
    pub fn open_path(&self) -> Result<(Vec<[f64; 3]>, Vec<u32>), ImportError> {
        let file = &self.source.file;
        let vline = |v: u32| self.source.vertex_line(v);
        let mut next: Vec<Vec<u32>> = vec![Vec::new(); self.vertices.len()];
        for (k, s) in self.segments.iter().enumerate() {
            let line = self.segment_lines.get(k).map_or(0, |&l| l as usize);
            if s[0] == s[1] {
                return Err(ImportError::new(
                    file,
                    line,
                    "a segment joins a vertex to itself; a well path needs distinct ends",
                ));
            }
            for (a, b) in [(s[0], s[1]), (s[1], s[0])] {
                match next.get_mut(a as usize) {
                    Some(n) => n.push(b),
                    None => {
                        return Err(ImportError::new(file, line, "a segment names no vertex"));
                    }
                }
            }
        }
        if let Some(v) = (0..next.len()).find(|&v| next[v].len() > 2) {
            return Err(ImportError::new(
                file,
                vline(v as u32),
                format!(
                    "the line branches at this vertex ({} segments meet); a well path must be one chain of segments",
                    next[v].len()
                ),
            ));
        }
        let ends: Vec<u32> = (0..next.len() as u32)
            .filter(|&v| next[v as usize].len() == 1)
            .collect();
        let first_line = self.segment_lines.first().map_or(0, |&l| l as usize);
        if ends.is_empty() {
            return Err(ImportError::new(
                file,
                first_line,
                "the line is closed; a well path must have two ends",
            ));
        }
        let start = *ends
            .iter()
            .max_by(|&&a, &&b| {
                let (za, zb) = (self.vertices[a as usize][2], self.vertices[b as usize][2]);
                za.total_cmp(&zb).then(b.cmp(&a))
            })
            .expect("an end");
        let mut path = vec![start];
        let (mut prev, mut at) = (u32::MAX, start);
        while let Some(&n) = next[at as usize].iter().find(|&&n| n != prev) {
            path.push(n);
            (prev, at) = (at, n);
        }
        let used = next.iter().filter(|n| !n.is_empty()).count();
        if path.len() != used {
            return Err(ImportError::new(
                file,
                first_line,
                "the line is in several pieces; a well path must be one chain of segments",
            ));
        }
        let points = path.iter().map(|&v| self.vertices[v as usize]).collect();
        let lines = path.iter().map(|&v| vline(v) as u32).collect();
        Ok((points, lines))
    }
}
