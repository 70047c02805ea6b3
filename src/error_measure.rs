//! The error measure of SPEC.md section 7: the kernel's RGB565 output against
//! the f64 reference quantised as in section 6.
//!
//! ```
//! use fixshade::error_measure::compare;
//! use fixshade::reference::{quantize_rgb565, RefFrame};
//! let reference = RefFrame { width: 2, height: 1, color: vec![Some([0.5; 3]), None] };
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
/// use fixshade::error_measure::compare;
/// use fixshade::reference::RefFrame;
/// let color = vec![Some([1.0; 3]), Some([0.0; 3]), Some([0.0; 3]), None];
/// let reference = RefFrame { width: 4, height: 1, color };
/// // Exact white; black off by 1 LSB in green and blue; reference only; kernel only.
/// let stats = compare(&[0xFFFF, 0x0021, 0, 0x1234], &[true, true, false, true], &reference);
/// assert_eq!((stats.covered_both, stats.only_kernel, stats.only_reference), (2, 1, 1));
/// assert_eq!(stats.max_error, [0, 1, 1]);
/// assert!((stats.mean_error - 2.0 / 6.0).abs() < 1e-12);
/// assert_eq!((stats.exact_share, stats.coverage_mismatch_share), (0.5, 0.5));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorStats {
    /// Pixels drawn by both the kernel and the reference.
    pub covered_both: u64,
    /// Pixels drawn by the kernel only.
    pub only_kernel: u64,
    /// Pixels drawn by the reference only.
    pub only_reference: u64,
    /// Largest per-channel error (r, g, b) over pixels covered by both, in
    /// that channel's LSBs (1/31, 1/63, 1/31).
    pub max_error: [u32; 3],
    /// Mean error over the three channels and the pixels covered by both, in
    /// LSBs (each channel in its own LSBs); 0 when no pixel is covered by both.
    pub mean_error: f64,
    /// Share of pixels covered by both whose three channels all match; 1.0
    /// when no pixel is covered by both.
    pub exact_share: f64,
    /// `(only_kernel + only_reference) / max(1, covered_both + only_kernel + only_reference)`.
    pub coverage_mismatch_share: f64,
}

impl ErrorStats {
    /// True when every commonly covered pixel matches exactly and coverage agrees.
    ///
    /// ```
    /// use fixshade::error_measure::compare;
    /// use fixshade::reference::RefFrame;
    /// let empty = RefFrame { width: 0, height: 0, color: vec![] };
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
             coverage mismatches {} ({} kernel only, {} reference only, {:.3} %)",
            self.max_error[0],
            self.max_error[1],
            self.max_error[2],
            self.mean_error,
            self.exact_share * 100.0,
            self.covered_both,
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
/// channel's LSBs, over pixels covered by both; pixels covered by one side
/// only are counted apart. If the three slices differ in length, only their
/// common prefix is compared and the rest is ignored (no panic); use
/// [`compare_checked`] to treat that as an error.
///
/// ```
/// use fixshade::error_measure::compare;
/// use fixshade::reference::RefFrame;
/// let reference = RefFrame { width: 1, height: 1, color: vec![Some([1.0, 1.0, 1.0])] };
/// let stats = compare(&[0xFFFE], &[true], &reference);
/// assert_eq!(stats.max_error, [0, 0, 1]);
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
    if stats.covered_both > 0 {
        stats.mean_error = sum as f64 / (3.0 * stats.covered_both as f64);
        stats.exact_share = exact as f64 / stats.covered_both as f64;
    }
    let mismatches = stats.only_kernel + stats.only_reference;
    stats.coverage_mismatch_share =
        mismatches as f64 / (stats.covered_both + mismatches).max(1) as f64;
    stats
}

/// Why [`compare_checked`] refused to compare.
///
/// ```
/// use fixshade::error_measure::{compare_checked, LengthMismatch};
/// use fixshade::reference::RefFrame;
/// let reference = RefFrame { width: 2, height: 1, color: vec![None; 2] };
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
/// use fixshade::error_measure::compare_checked;
/// use fixshade::reference::RefFrame;
/// let reference = RefFrame { width: 1, height: 1, color: vec![None] };
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
