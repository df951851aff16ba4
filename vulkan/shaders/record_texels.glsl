// Records read through a uniform texel buffer of RGBA32UI, nine texels per record in the layout of
// core/shared/record_layout.h; floats are rebuilt bit for bit. The includer defines HPSF_RECORDS_BINDING.
layout(binding = HPSF_RECORDS_BINDING) uniform usamplerBuffer record_texels;

const int kTexelsPerRecord = 9;

Record LoadRecord(uint index) {
  int first = int(index) * kTexelsPerRecord;
  Record r;
  r.position = uintBitsToFloat(texelFetch(record_texels, first));
  r.normal = uintBitsToFloat(texelFetch(record_texels, first + 1));
  r.tangent = uintBitsToFloat(texelFetch(record_texels, first + 2));
  r.bitangent = uintBitsToFloat(texelFetch(record_texels, first + 3));
  r.previous = uintBitsToFloat(texelFetch(record_texels, first + 4));
  r.contribution = uintBitsToFloat(texelFetch(record_texels, first + 5));
  r.throughput = uintBitsToFloat(texelFetch(record_texels, first + 6));
  r.radiance_before = uintBitsToFloat(texelFetch(record_texels, first + 7));
  r.path = texelFetch(record_texels, first + 8);
  return r;
}

// Only what resolve reads (contribution, throughput, radiance_before, path): four texels of the nine; the
// geometric fields are left unset.
Record LoadShadingFields(uint index) {
  int first = int(index) * kTexelsPerRecord;
  Record r;
  r.contribution = uintBitsToFloat(texelFetch(record_texels, first + 5));
  r.throughput = uintBitsToFloat(texelFetch(record_texels, first + 6));
  r.radiance_before = uintBitsToFloat(texelFetch(record_texels, first + 7));
  r.path = texelFetch(record_texels, first + 8);
  return r;
}
