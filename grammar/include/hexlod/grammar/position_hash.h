// Position-keyed randomness (Biston's seed map): every stochastic decision hashes the
// scene seed, the building id and the derivation path, never a call counter, so that a
// batch regenerates the same terminals in any order and on any thread.
#pragma once

#include <cstdint>

namespace hexlod::grammar {

// splitmix64 finaliser: cheap and with full avalanche, enough for picking successors.
constexpr uint64_t mixBits(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

constexpr uint64_t combineKey(uint64_t key, uint64_t value) {
    return mixBits(key ^ mixBits(value));
}

// A uniform float in [0, 1) from the top 24 bits of a key.
constexpr float unitFloat(uint64_t key) {
    return static_cast<float>(key >> 40) * (1.0f / 16777216.0f);
}

} // namespace hexlod::grammar
