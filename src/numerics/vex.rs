//! Whether the hot passes (the contact steps and the free flight, the recorder's projections,
//! the floors' stations) run as their copies compiled for AVX: the same
//! Rust code, the same IEEE operations lane by lane and in the same order (AVX brings no fused
//! multiply–add, and none is enabled), only encoded in the three-operand VEX form (`vmulpd`
//! with a destination of its own), so that the register copies the two-operand SSE2 form
//! needs before every product that keeps an operand go away. The results are the same to the
//! last bit on either path; only the instruction count differs (x86-64 with AVX, detected once
//! per process by the standard library, then a load).

/// Whether this processor runs the AVX copies (`false` off x86-64).
#[inline]
pub(crate) fn available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Defines `fn $name` as a dispatcher to `$body` (the work, `#[inline(always)]`, written once)
/// compiled twice: as `$vex`, with `#[target_feature(enable = "avx")]`, where [`available`],
/// else as it is. The same Rust code on both paths (module doc: the same bits). Two forms: a
/// method on `&mut self`, or a free function with an optional const parameter.
///
/// ```ignore
/// avx_copy! {
///     /// Docs of the dispatcher.
///     pub(super) fn step(&mut self, h: f64) -> bool => step_vex, step_body
/// }
/// ```
macro_rules! avx_copy {
    (
        $(#[$attr:meta])*
        $vis:vis fn $name:ident(&mut self $(, $arg:ident: $ty:ty)* $(,)?) $(-> $ret:ty)?
        => $vex:ident, $body:ident
    ) => {
        $(#[$attr])*
        $vis fn $name(&mut self $(, $arg: $ty)*) $(-> $ret)? {
            #[cfg(target_arch = "x86_64")]
            if $crate::numerics::vex::available() {
                // SAFETY: the processor has AVX
                return unsafe { self.$vex($($arg),*) };
            }
            self.$body($($arg),*)
        }

        /// The dispatcher's AVX copy (`numerics::vex`: the same bits). Safety: the processor
        /// has AVX.
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx")]
        #[allow(clippy::too_many_arguments)]
        unsafe fn $vex(&mut self $(, $arg: $ty)*) $(-> $ret)? {
            self.$body($($arg),*)
        }
    };
    (
        $(#[$attr:meta])*
        $vis:vis fn $name:ident $(<const $c:ident: $cty:ty>)? ($($arg:ident: $ty:ty),* $(,)?)
            $(-> $ret:ty)?
        => $vex:ident, $body:ident
    ) => {
        $(#[$attr])*
        $vis fn $name $(<const $c: $cty>)? ($($arg: $ty),*) $(-> $ret)? {
            #[cfg(target_arch = "x86_64")]
            if $crate::numerics::vex::available() {
                // SAFETY: the processor has AVX
                return unsafe { $vex $(::<$c>)? ($($arg),*) };
            }
            $body $(::<$c>)? ($($arg),*)
        }

        /// The dispatcher's AVX copy (`numerics::vex`: the same bits). Safety: the processor
        /// has AVX.
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx")]
        #[allow(clippy::too_many_arguments)]
        unsafe fn $vex $(<const $c: $cty>)? ($($arg: $ty),*) $(-> $ret)? {
            $body $(::<$c>)? ($($arg),*)
        }
    };
}
pub(crate) use avx_copy;
