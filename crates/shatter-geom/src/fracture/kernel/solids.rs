//! A cut piece as solids: its connected components, each cavity's wall (a component of
//! negative volume, wound inward) joined to the component that encloses it. A cell that
//! holds a whole cavity of a hollow input is one solid with two shells, not an outer
//! solid and a fragment of negative volume.

use glam::DVec3;

use super::Piece;

impl Piece {
    /// The piece's edge-connected components ([`Piece::components`]), with each one of
    /// negative volume (a cavity's wall) appended to the smallest component of positive
    /// volume whose winding number is ½ or more at the cavity wall's vertices (the
    /// median over a few of them). A negative component that nothing encloses stays on
    /// its own, for the volume checks to refuse.
    pub fn solids(self) -> Vec<Piece> {
        with_cavities(self.components())
    }
}

/// Closed parts of one cut (components), each of negative volume (a cavity's wall)
/// appended to the smallest part of positive volume that encloses it: see
/// [`Piece::solids`].
pub(crate) fn with_cavities(parts: Vec<Piece>) -> Vec<Piece> {
    if parts.len() < 2 {
        return parts;
    }
    let volumes: Vec<f64> = parts.iter().map(Piece::volume).collect();
    if volumes.iter().all(|&v| v >= 0.0) {
        return parts;
    }
    let mut owner: Vec<Option<usize>> = vec![None; parts.len()];
    for (i, part) in parts.iter().enumerate() {
        if volumes[i] >= 0.0 || part.pos.is_empty() {
            continue;
        }
        let step = (part.pos.len() / 5).max(1);
        let probes: Vec<DVec3> = part.pos.iter().step_by(step).take(5).copied().collect();
        owner[i] = (0..parts.len())
            .filter(|&j| volumes[j] > 0.0)
            .filter(|&j| {
                let mut w: Vec<f64> = probes.iter().map(|&p| parts[j].winding(p)).collect();
                w.sort_by(f64::total_cmp);
                w[w.len() / 2] >= 0.5
            })
            .min_by(|&a, &b| volumes[a].total_cmp(&volumes[b]));
    }
    let mut slots: Vec<Option<Piece>> = parts.into_iter().map(Some).collect();
    for (i, o) in owner.iter().enumerate() {
        if let Some(j) = *o {
            let cavity = slots[i].take().unwrap_or_default();
            if let Some(host) = slots[j].as_mut() {
                host.append(cavity);
            }
        }
    }
    slots.into_iter().flatten().collect()
}

impl Piece {
    /// Adds `other`'s positions, triangles and faces to this piece (no welding: the two
    /// share no vertex).
    fn append(&mut self, other: Piece) {
        let base = self.pos.len() as u32;
        self.pos.extend(other.pos);
        self.tris
            .extend(other.tris.iter().map(|t| t.map(|i| i + base)));
        self.tags.extend(other.tags);
        for mut face in other.faces {
            for (a, b) in &mut face.edges {
                *a += base;
                *b += base;
            }
            self.faces.push(face);
        }
    }

    /// The generalized winding number of the piece at `p` (its triangles, and each face
    /// as the fan of its edges from the face's first vertex, which adds up to the
    /// face's polygon).
    fn winding(&self, p: DVec3) -> f64 {
        let solid_angle = |a: u32, b: u32, c: u32| {
            let [a, b, c] = [a, b, c].map(|i| self.pos[i as usize] - p);
            let (la, lb, lc) = (a.length(), b.length(), c.length());
            let num = a.dot(b.cross(c));
            let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
            2.0 * num.atan2(den)
        };
        let tris: f64 = self
            .tris
            .iter()
            .map(|t| solid_angle(t[0], t[1], t[2]))
            .sum();
        let faces: f64 = self
            .faces
            .iter()
            .filter_map(|f| {
                let &(apex, _) = f.edges.first()?;
                Some(
                    f.edges
                        .iter()
                        .filter(|&&(a, b)| a != apex && b != apex)
                        .map(|&(a, b)| solid_angle(apex, a, b))
                        .sum::<f64>(),
                )
            })
            .sum();
        (tris + faces) / (4.0 * std::f64::consts::PI)
    }
}
