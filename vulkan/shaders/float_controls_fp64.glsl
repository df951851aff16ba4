// The resolve pass works in double, as core/resolve does: round-to-nearest-even and signed-zero/Inf/NaN
// preservation declared for 64-bit floats too, so its adds, multiplies, divides and conversions round as C++'s.
spirv_execution_mode(extensions = ["SPV_KHR_float_controls"], capabilities = [4467], 4462, 64);  // RoundingModeRTE
spirv_execution_mode(extensions = ["SPV_KHR_float_controls"], capabilities = [4466], 4461, 64);  // SignedZeroInfNanPreserve
