// KeyResult as keys.comp writes it to memory: eight words in two 16-byte vectors instead of twelve in three.
// lavapipe stores lane by lane and word by word, one loop per vector store; without the third vector keys.comp
// took 67 ms instead of 72 for 2M records. The four words left out carry nothing the shader computes: the
// reserved key word `extra` and the two padding words are always 0, and level and status share one word.
// Unpacking is one-to-one: it restores a C++ KeyResult exactly, and a shader that wrote any other words
// unpacks to a different result, so the comparison with the C++ one fails. A full key's high word is not packed:
// it is a function of the key words (core/shared/full_key.h), and its low word, the fingerprint's place, is.
#ifndef HPSF_CORE_SHARED_PACKED_KEY_H
#define HPSF_CORE_SHARED_PACKED_KEY_H

#include "key.h"

HPSF_SHARED_BEGIN

// The level is in [-127, 128] (an unbiased float exponent), so its low 16 bits keep it; status is 0..2.
const uint kPackedLevelMask = 0xFFFFu;
const uint kPackedStatusShift = 16u;

// Key words 0..3: cell x, y, z and the level word.
HPSF_FN uvec4 PackedKeyCell(KeyResult k) {
  return uvec4(k.words.cell_x, k.words.cell_y, k.words.cell_z, k.words.level);
}

// The normal bucket, slot0, the fingerprint, and the level (low 16 bits) with the status (high 16 bits).
HPSF_FN uvec4 PackedKeyHashes(KeyResult k) {
  uint level_and_status = (uint(k.level) & kPackedLevelMask) | (k.status << kPackedStatusShift);
  return uvec4(k.words.normal, k.slot0, k.fingerprint, level_and_status);
}

HPSF_FN KeyResult UnpackKey(uvec4 cell, uvec4 hashes, uint key_identity) {
  KeyResult k;
  k.words.cell_x = cell.x;
  k.words.cell_y = cell.y;
  k.words.cell_z = cell.z;
  k.words.level = cell.w;
  k.words.normal = hashes.x;
  k.words.extra = 0u;
  k.slot0 = hashes.y;
  k.fingerprint = hashes.z;
  k.level = int(hashes.w << kPackedStatusShift) >> int(kPackedStatusShift);  // sign-extends the low 16 bits
  k.status = hashes.w >> kPackedStatusShift;
  k.identity_high = key_identity == kIdentityFull && k.status == kKeyed ? FullKey(k.words).y : 0u;
  k.padding1 = 0u;
  return k;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_PACKED_KEY_H
