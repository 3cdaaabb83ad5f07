// XXH3 compiled here, inline: it then uses this build's vector instructions
// (-march), and the digest is the same whatever they are.
#include "base/util/checksum.h"

#define XXH_INLINE_ALL
#include <xxhash.h>

namespace zs {

struct Checksum64::State {
  XXH3_state_t s;
};

Checksum64::Checksum64() : state_(new State{}) { XXH3_64bits_reset(&state_->s); }
Checksum64::~Checksum64() = default;

void Checksum64::update(const void* data, size_t n) { XXH3_64bits_update(&state_->s, data, n); }
uint64_t Checksum64::digest() const { return XXH3_64bits_digest(&state_->s); }

uint64_t checksum64(const void* data, size_t n) { return XXH3_64bits(data, n); }

}  // namespace zs
