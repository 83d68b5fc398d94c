//! The frame classifier of the field experiment (Sung and Tokekar, section 7): a downward
//! camera image is split 3 × 3; the centre region is the cell below, the top, right, bottom
//! and left regions its four neighbours. Each image is converted to grey, thresholded at
//! intensity 150, and dilated 7 times so that the gaps in grass fill with white; a region
//! whose share of dark pixels reaches a threshold shows the (dark) region of interest.

use image::GrayImage;
use imageproc::distance_transform::Norm;

/// The classifier's parameters. The defaults are the paper's, except the dark share, which
/// the paper does not state.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FrameClassifier {
    /// Pixels brighter than this are white (the paper: 150).
    pub intensity_threshold: u8,
    /// Dilations of the white pixels by one pixel (3 × 3), the paper: 7.
    pub dilations: u8,
    /// A region shows the region of interest when at least this share of its pixels is dark.
    /// The paper does not give it; 0.3 is our choice (a region of interest cell keeps more
    /// than half of its pixels dark after the dilation eats 7 pixels from its light sides).
    pub dark_share: f64,
}

impl Default for FrameClassifier {
    fn default() -> Self {
        Self { intensity_threshold: 150, dilations: 7, dark_share: 0.3 }
    }
}

/// What the classifier saw in one frame.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FrameVerdict {
    /// The dark share of the 3 × 3 regions, row by row from the top left.
    pub dark: [[f64; 3]; 3],
    /// Centre, then north (top), east (right), south (bottom), west (left): region of
    /// interest or not.
    pub centre: bool,
    /// North, east, south, west.
    pub sides: [bool; 4],
}

impl FrameClassifier {
    /// The binary image after thresholding and dilation (white 255 = background).
    pub fn binarise(&self, grey: &GrayImage) -> GrayImage {
        let mut bin = imageproc::contrast::threshold(
            grey,
            self.intensity_threshold,
            imageproc::contrast::ThresholdType::Binary,
        );
        if self.dilations > 0 {
            bin = imageproc::morphology::dilate(&bin, Norm::LInf, self.dilations);
        }
        bin
    }

    /// Classifies a grey frame. Frames smaller than 3 × 3 pixels show nothing.
    pub fn classify(&self, grey: &GrayImage) -> FrameVerdict {
        let bin = self.binarise(grey);
        let (w, h) = (bin.width(), bin.height());
        let mut dark = [[0.0; 3]; 3];
        if w >= 3 && h >= 3 {
            for (gy, row) in dark.iter_mut().enumerate() {
                for (gx, d) in row.iter_mut().enumerate() {
                    let (x0, x1) = (w * gx as u32 / 3, w * (gx as u32 + 1) / 3);
                    let (y0, y1) = (h * gy as u32 / 3, h * (gy as u32 + 1) / 3);
                    let mut n = 0u32;
                    for y in y0..y1 {
                        for x in x0..x1 {
                            n += u32::from(bin.get_pixel(x, y)[0] == 0);
                        }
                    }
                    *d = f64::from(n) / f64::from((x1 - x0) * (y1 - y0));
                }
            }
        }
        let on = |d: f64| d >= self.dark_share;
        FrameVerdict {
            dark,
            centre: on(dark[1][1]),
            sides: [on(dark[0][1]), on(dark[1][2]), on(dark[2][1]), on(dark[1][0])],
        }
    }

    /// Classifies a colour frame (converted to grey first).
    pub fn classify_rgb(&self, rgb: &image::RgbImage) -> FrameVerdict {
        self.classify(&image::DynamicImage::ImageRgb8(rgb.clone()).to_luma8())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Luma;

    /// A 3 × 3 frame of 30-pixel regions: dark where `roi[row][col]`, grass with dark gaps
    /// elsewhere.
    fn frame(roi: [[bool; 3]; 3]) -> GrayImage {
        GrayImage::from_fn(90, 90, |x, y| {
            let (gx, gy) = ((x / 30) as usize, (y / 30) as usize);
            let v = if roi[gy][gx] {
                60
            } else if (x / 2 + y / 2) % 5 == 0 {
                90 // a gap between grass blades: dark, but small
            } else {
                200
            };
            Luma([v])
        })
    }

    #[test]
    fn decides_the_centre_and_four_neighbours() {
        let roi = [[false, true, false], [true, true, false], [false, false, false]];
        let v = FrameClassifier::default().classify(&frame(roi));
        assert!(v.centre);
        assert_eq!(v.sides, [true, false, false, true]);
        assert!(v.dark[2][2] < 0.01, "grass gaps are filled by the dilation: {:?}", v.dark);
    }

    #[test]
    fn grass_gaps_would_fool_it_without_dilation() {
        let roi = [[false; 3]; 3];
        let plain =
            FrameClassifier { dilations: 0, dark_share: 0.15, ..FrameClassifier::default() };
        let v = plain.classify(&frame(roi));
        assert!(v.sides.iter().any(|&s| s), "without dilation the gaps look dark");
        let v = FrameClassifier { dark_share: 0.15, ..FrameClassifier::default() }
            .classify(&frame(roi));
        assert!(!v.centre && v.sides == [false; 4]);
    }

    #[test]
    fn all_dark_and_all_light() {
        let c = FrameClassifier::default();
        assert_eq!(c.classify(&frame([[true; 3]; 3])).sides, [true; 4]);
        let v = c.classify(&frame([[false; 3]; 3]));
        assert!(!v.centre && v.sides == [false; 4]);
        assert!(!c.classify(&GrayImage::new(2, 2)).centre);
    }
}
