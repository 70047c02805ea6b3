//! The error measure of SPEC.md section 7: the kernel's RGB565 output against
//! the f64 reference quantised as in section 6.
//!
//! Pixels covered by one side only, depth ties and model steps (the
//! reference's [`tie`](RefFrame::tie) and [`step`](RefFrame::step) flags)
//! are counted apart; the colour error is measured over the other pixels
//! both sides cover.
//!
//! ```
//! use fixshade_host::error_measure::compare;
//! use fixshade_host::reference::{quantize_rgb565, RefFrame};
//! let reference = RefFrame::new(2, 1, vec![Some([0.5; 3]), None]);
//! let kernel = [quantize_rgb565([0.5; 3]), 0];
//! let stats = compare(&kernel, &[true, false], &reference);
//! assert_eq!(stats.covered_both, 1);
//! assert_eq!(stats.exact_share, 1.0);
//! ```

use crate::reference::{quantize_rgb565, RefFrame};
use std::fmt;

/// Result of [`compare`].
///
/// ```
/// use fixshade_host::error_measure::compare;
/// use fixshade_host::reference::RefFrame;
/// let color = vec![Some([1.0; 3]), Some([0.0; 3]), Some([0.0; 3]), None, Some([0.0; 3])];
/// let mut reference = RefFrame::new(5, 1, color);
/// reference.tie[4] = true;
/// // Exact white; black off by 1 LSB in green and blue; reference only;
/// // kernel only; a depth tie drawn in another colour.
/// let kernel = [0xFFFF, 0x0021, 0, 0x1234, 0xFFFF];
/// let stats = compare(&kernel, &[true, true, false, true, true], &reference);
/// assert_eq!((stats.covered_both, stats.only_kernel, stats.only_reference), (3, 1, 1));
/// assert_eq!((stats.depth_ties, stats.model_steps, stats.compared), (1, 0, 2));
/// assert_eq!(stats.max_error, [0, 1, 1]); // the tie is not held to the bound
/// assert!((stats.mean_error - 2.0 / 6.0).abs() < 1e-12);
/// assert_eq!((stats.exact_share, stats.coverage_mismatch_share), (0.5, 2.0 / 5.0));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorStats {
    /// Pixels drawn by both the kernel and the reference.
    pub covered_both: u64,
    /// Pixels drawn by the kernel only.
    pub only_kernel: u64,
    /// Pixels drawn by the reference only.
    pub only_reference: u64,
    /// Pixels covered by both that the reference flags as depth ties
    /// ([`RefFrame::tie`]): not held to the colour bound.
    pub depth_ties: u64,
    /// Pixels covered by both that the reference flags as model steps
    /// ([`RefFrame::step`]): not held to the colour bound. A pixel that is
    /// both a tie and a step is counted in both.
    pub model_steps: u64,
    /// Pixels covered by both that are neither a tie nor a step: those the
    /// colour error below is measured over.
    pub compared: u64,
    /// Largest per-channel error (r, g, b) over the compared pixels, in
    /// that channel's LSBs (1/31, 1/63, 1/31).
    pub max_error: [u32; 3],
    /// Mean error over the three channels and the compared pixels, in LSBs
    /// (each channel in its own LSBs); 0 when no pixel is compared.
    pub mean_error: f64,
    /// Share of the compared pixels whose three channels all match; 1.0
    /// when no pixel is compared.
    pub exact_share: f64,
    /// `(only_kernel + only_reference) / max(1, covered_both + only_kernel + only_reference)`.
    pub coverage_mismatch_share: f64,
}

impl ErrorStats {
    /// True when every compared pixel matches exactly and coverage agrees
    /// (depth ties and model steps are not looked at).
    ///
    /// ```
    /// use fixshade_host::error_measure::compare;
    /// use fixshade_host::reference::RefFrame;
    /// let empty = RefFrame::new(0, 0, vec![]);
    /// assert!(compare(&[], &[], &empty).is_exact());
    /// ```
    pub fn is_exact(&self) -> bool {
        self.max_error == [0; 3] && self.only_kernel == 0 && self.only_reference == 0
    }
}

impl fmt::Display for ErrorStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "max r/g/b {}/{}/{} LSB, mean {:.4} LSB, exact {:.2} % of {} px, \
             depth ties {}, model steps {}, \
             coverage mismatches {} ({} kernel only, {} reference only, {:.3} %)",
            self.max_error[0],
            self.max_error[1],
            self.max_error[2],
            self.mean_error,
            self.exact_share * 100.0,
            self.compared,
            self.depth_ties,
            self.model_steps,
            self.only_kernel + self.only_reference,
            self.only_kernel,
            self.only_reference,
            self.coverage_mismatch_share * 100.0,
        )
    }
}

/// Splits RGB565 into its (r5, g6, b5) channels.
fn channels(c: u16) -> [u32; 3] {
    [
        u32::from(c >> 11),
        u32::from((c >> 5) & 0x3F),
        u32::from(c & 0x1F),
    ]
}

/// Compares a kernel frame (raw RGB565 pixels plus a coverage mask, both
/// row-major like `reference.color`) with the reference.
///
/// The error of a channel is `|kernel − quantised reference|` in that
/// channel's LSBs, over pixels covered by both that the reference flags
/// neither as a depth tie nor as a model step; pixels covered by one side
/// only, ties and steps are counted apart. If the three slices differ in
/// length, only their common prefix is compared and the rest is ignored (no
/// panic; missing flags count as unset); use [`compare_checked`] to treat
/// that as an error.
///
/// ```
/// use fixshade_host::error_measure::compare;
/// use fixshade_host::reference::RefFrame;
/// let mut reference = RefFrame::new(2, 1, vec![Some([1.0, 1.0, 1.0]); 2]);
/// reference.step[1] = true; // e.g. on a spot's cone edge
/// let stats = compare(&[0xFFFE, 0x0000], &[true; 2], &reference);
/// assert_eq!(stats.max_error, [0, 0, 1]);
/// assert_eq!((stats.model_steps, stats.compared), (1, 1));
/// ```
pub fn compare(kernel_pixels: &[u16], kernel_covered: &[bool], reference: &RefFrame) -> ErrorStats {
    let n = kernel_pixels
        .len()
        .min(kernel_covered.len())
        .min(reference.color.len());
    let mut stats = ErrorStats {
        covered_both: 0,
        only_kernel: 0,
        only_reference: 0,
        depth_ties: 0,
        model_steps: 0,
        compared: 0,
        max_error: [0; 3],
        mean_error: 0.0,
        exact_share: 1.0,
        coverage_mismatch_share: 0.0,
    };
    let mut sum: u64 = 0;
    let mut exact: u64 = 0;
    for i in 0..n {
        match (kernel_covered[i], reference.color[i]) {
            (true, Some(c)) => {
                stats.covered_both += 1;
                let tie = reference.tie.get(i).copied().unwrap_or(false);
                let step = reference.step.get(i).copied().unwrap_or(false);
                stats.depth_ties += u64::from(tie);
                stats.model_steps += u64::from(step);
                if tie || step {
                    continue;
                }
                stats.compared += 1;
                let k = channels(kernel_pixels[i]);
                let r = channels(quantize_rgb565(c));
                let mut all = true;
                for ch in 0..3 {
                    let e = k[ch].abs_diff(r[ch]);
                    stats.max_error[ch] = stats.max_error[ch].max(e);
                    sum += u64::from(e);
                    all &= e == 0;
                }
                exact += u64::from(all);
            }
            (true, None) => stats.only_kernel += 1,
            (false, Some(_)) => stats.only_reference += 1,
            (false, None) => {}
        }
    }
    if stats.compared > 0 {
        stats.mean_error = sum as f64 / (3.0 * stats.compared as f64);
        stats.exact_share = exact as f64 / stats.compared as f64;
    }
    let mismatches = stats.only_kernel + stats.only_reference;
    stats.coverage_mismatch_share =
        mismatches as f64 / (stats.covered_both + mismatches).max(1) as f64;
    stats
}

/// Why [`compare_checked`] refused to compare.
///
/// ```
/// use fixshade_host::error_measure::{compare_checked, LengthMismatch};
/// use fixshade_host::reference::RefFrame;
/// let reference = RefFrame::new(2, 1, vec![None; 2]);
/// let err = compare_checked(&[0; 2], &[false; 3], &reference).unwrap_err();
/// assert_eq!(err, LengthMismatch { kernel_pixels: 2, kernel_covered: 3, reference: 2 });
/// assert!(err.to_string().contains("3 coverage flags"));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LengthMismatch {
    /// `kernel_pixels.len()`.
    pub kernel_pixels: usize,
    /// `kernel_covered.len()`.
    pub kernel_covered: usize,
    /// `reference.color.len()`.
    pub reference: usize,
}

impl fmt::Display for LengthMismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "frame sizes differ: {} kernel pixels, {} coverage flags, {} reference pixels",
            self.kernel_pixels, self.kernel_covered, self.reference
        )
    }
}

impl std::error::Error for LengthMismatch {}

/// As [`compare`], but an error when the three slices differ in length.
///
/// ```
/// use fixshade_host::error_measure::compare_checked;
/// use fixshade_host::reference::RefFrame;
/// let reference = RefFrame::new(1, 1, vec![None]);
/// assert!(compare_checked(&[0, 0], &[false, false], &reference).is_err());
/// ```
pub fn compare_checked(
    kernel_pixels: &[u16],
    kernel_covered: &[bool],
    reference: &RefFrame,
) -> Result<ErrorStats, LengthMismatch> {
    let n = reference.color.len();
    if kernel_pixels.len() != n || kernel_covered.len() != n {
        return Err(LengthMismatch {
            kernel_pixels: kernel_pixels.len(),
            kernel_covered: kernel_covered.len(),
            reference: n,
        });
    }
    Ok(compare(kernel_pixels, kernel_covered, reference))
}
