// Declares round-to-nearest-even and signed-zero/Inf/NaN preservation for 32-bit floats (SPV_KHR_float_controls),
// so adds and multiplies on the key path round exactly as C++ does. The host checks the device supports both.
#extension GL_EXT_spirv_intrinsics : require
spirv_execution_mode(extensions = ["SPV_KHR_float_controls"], capabilities = [4467], 4462, 32);  // RoundingModeRTE
spirv_execution_mode(extensions = ["SPV_KHR_float_controls"], capabilities = [4466], 4461, 32);  // SignedZeroInfNanPreserve
