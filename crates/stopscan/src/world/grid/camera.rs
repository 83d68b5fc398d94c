//! A synthetic downward camera, so that the whole field pipeline runs in simulation: it renders
//! frames of the ground truth (dark region of interest on grass with dark gaps), adds a pointing
//! error, blur and noise, and now and then a shadow (a false positive) or glare (a false
//! negative) over one ninth of the frame; the frame classifier then decides.

use image::{GrayImage, Luma};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::GridRoi;
use crate::algorithm::frame::FrameClassifier;
use crate::protocol::grid::{Cell, Frame};

/// The camera and its classifier.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CameraModel {
    /// Frames per scan (the paper: 5, voted 3 of 5).
    pub frames: usize,
    /// Pixels across one cell (a frame is three cells wide).
    pub pixels_per_cell: u32,
    /// Standard deviation of the pixel noise, grey levels.
    pub noise: f64,
    /// Standard deviation of the Gaussian blur, pixels (0: none).
    pub blur: f64,
    /// Largest pointing error (pitch and roll), pixels in each direction.
    pub pointing_error: u32,
    /// Probability that a ninth of a frame showing no region gets a shadow.
    pub false_positive: f64,
    /// Probability that a ninth of a frame showing the region gets glare.
    pub false_negative: f64,
    /// The classifier.
    pub classifier: FrameClassifier,
}

impl Default for CameraModel {
    fn default() -> Self {
        Self {
            frames: 5,
            pixels_per_cell: 32,
            noise: 12.0,
            blur: 1.0,
            pointing_error: 3,
            false_positive: 0.05,
            false_negative: 0.05,
            classifier: FrameClassifier::default(),
        }
    }
}

/// Grey levels of the synthetic scene.
const ROI_GREY: f64 = 70.0;
const GRASS_GREY: f64 = 185.0;
const GAP_GREY: f64 = 95.0;
const SHADOW_GREY: f64 = 55.0;
const GLARE_GREY: f64 = 235.0;

impl CameraModel {
    /// Renders frame `k` over `cell` for robot `robot` at time `clock`. The same arguments
    /// and seed give the same image.
    pub fn render(
        &self,
        roi: &GridRoi,
        cell: Cell,
        seed: u64,
        robot: usize,
        clock: f64,
        k: usize,
    ) -> GrayImage {
        let mut rng = ChaCha8Rng::seed_from_u64(mix(&[
            seed,
            robot as u64,
            u64::from(cell[0] as u32),
            u64::from(cell[1] as u32),
            clock.to_bits(),
            k as u64,
        ]));
        let p = self.pixels_per_cell.max(3);
        let size = 3 * p;
        let e = i64::from(self.pointing_error);
        let (ox, oy) = (rng.random_range(-e..=e), rng.random_range(-e..=e));
        // Shadows and glare over whole ninths of the frame.
        let mut patch = [[None; 3]; 3];
        for (gy, row) in patch.iter_mut().enumerate() {
            for (gx, v) in row.iter_mut().enumerate() {
                let c = [cell[0] + gy as i32 - 1, cell[1] + gx as i32 - 1];
                let inside = roi.contains(c);
                if !inside && rng.random_bool(self.false_positive.clamp(0.0, 1.0)) {
                    *v = Some(SHADOW_GREY);
                } else if inside && rng.random_bool(self.false_negative.clamp(0.0, 1.0)) {
                    *v = Some(GLARE_GREY);
                }
            }
        }
        let s = roi.cell_size();
        let scale = f64::from(p);
        let half = f64::from(size) / 2.0;
        let mut img = GrayImage::from_fn(size, size, |x, y| {
            let u = (f64::from(x) + 0.5 + ox as f64 - half) / scale; // cells east of the centre
            let v = (f64::from(y) + 0.5 + oy as f64 - half) / scale; // cells south
            let here = match roi.shape() {
                Some(shape) => {
                    let pt = [(f64::from(cell[1]) + u) * s, -(f64::from(cell[0]) + v) * s];
                    !matches!(shape.locate(pt), crate::geometry::Location::Outside)
                }
                None => roi.contains([cell[0] + v.round() as i32, cell[1] + u.round() as i32]),
            };
            let grey = if here {
                ROI_GREY
            } else if (x / 2 + y / 2) % 5 == 0 {
                GAP_GREY
            } else {
                GRASS_GREY
            };
            let (gx, gy) = ((x / p).min(2) as usize, (y / p).min(2) as usize);
            Luma([patch[gy][gx].unwrap_or(grey) as u8])
        });
        if self.blur > 0.0 {
            img = imageproc::filter::gaussian_blur_f32(&img, self.blur as f32);
        }
        if self.noise > 0.0 {
            for px in img.pixels_mut() {
                let n = gaussian(&mut rng) * self.noise;
                px[0] = (f64::from(px[0]) + n).round().clamp(0.0, 255.0) as u8;
            }
        }
        img
    }

    /// The frames of one scan, classified.
    pub fn frames(
        &self,
        roi: &GridRoi,
        cell: Cell,
        seed: u64,
        robot: usize,
        clock: f64,
    ) -> Vec<Frame> {
        (0..self.frames)
            .map(|k| {
                let v = self.classifier.classify(&self.render(roi, cell, seed, robot, clock, k));
                Frame { centre: v.centre, sides: v.sides }
            })
            .collect()
    }
}

/// A standard normal sample (Box–Muller).
fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = rng.random_range(f64::EPSILON..1.0);
    let u2: f64 = rng.random_range(0.0..1.0);
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// Mixes several words into one seed (SplitMix64 steps).
fn mix(words: &[u64]) -> u64 {
    let mut h = 0x9e37_79b9_7f4a_7c15_u64;
    for &w in words {
        h ^= w;
        h = h.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = h;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        h = z ^ (z >> 31);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clean_camera_sees_the_truth() {
        let roi =
            GridRoi::new("t", [[0, 0], [0, 1], [1, 0], [1, 1], [-1, 0]], [0, 0], 1.0).unwrap();
        let clean = CameraModel {
            noise: 0.0,
            blur: 0.0,
            pointing_error: 0,
            false_positive: 0.0,
            false_negative: 0.0,
            ..CameraModel::default()
        };
        for c in [[0, 0], [1, 1], [-1, 0], [0, 3]] {
            let f = clean.frames(&roi, c, 7, 0, 0.0);
            let truth = Frame {
                centre: roi.contains(c),
                sides: std::array::from_fn(|i| {
                    roi.contains(crate::protocol::grid::neighbour(c, i))
                }),
            };
            assert!(f.iter().all(|x| *x == truth), "{c:?}: {f:?} vs {truth:?}");
        }
    }

    #[test]
    fn noisy_frames_are_seeded() {
        let roi = GridRoi::random(30, 1).unwrap();
        let cam = CameraModel::default();
        let a = cam.render(&roi, [0, 0], 3, 1, 2.5, 0);
        assert_eq!(a, cam.render(&roi, [0, 0], 3, 1, 2.5, 0));
        assert_ne!(a, cam.render(&roi, [0, 0], 4, 1, 2.5, 0));
    }
}
