// The compute-only control of a scaling measurement: a fixed amount of
// register-only arithmetic split into independent chunks, run on the current TBB
// arena. Its 2-thread/1-thread ratio is what the machine could give any stage in
// that run: on a shared host it drops below 2 when the host slows both vCPUs,
// which a CPU share cannot see (both threads still run all the time).
#pragma once
#include <cstdint>

namespace penumbra {

// One pass of the control: 256 chunks of two xorshift64 chains, 2^20 steps each,
// nothing shared and no memory traffic. Returns a value every chunk feeds, so the
// optimiser keeps the work.
uint64_t computeControl();

}  // namespace penumbra
