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
