#include "backend/walk_interleaver.h"

#include <memory>
#include <utility>

#include <boost/context/protected_fixedsize_stack.hpp>

// AddressSanitizer tracks one stack per thread; it is told of each switch
// to and from a fiber's stack, or it would take the other stack's frames
// for overflows (GCC says so with __SANITIZE_ADDRESS__, clang with
// __has_feature).
#if defined(__SANITIZE_ADDRESS__)
#define SPECTRACE_FIBERS_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SPECTRACE_FIBERS_UNDER_ASAN 1
#endif
#endif
#if defined(SPECTRACE_FIBERS_UNDER_ASAN)
#include <sanitizer/asan_interface.h>
#include <sanitizer/common_interface_defs.h>
#endif

namespace spectrace {

namespace {

// The kernel needs a few kilobytes of stack; a fiber's is 1 MiB of address
// space, touched only as deep as it goes, with a guard page below it so
// that an overflow faults instead of writing over another fiber's.
constexpr size_t kFiberStackBytes = size_t(1) << 20;

void startSwitch(void** fakeStackSave, const void* bottom, size_t size) {
#if defined(SPECTRACE_FIBERS_UNDER_ASAN)
  __sanitizer_start_switch_fiber(fakeStackSave, bottom, size);
#else
  (void)fakeStackSave, (void)bottom, (void)size;
#endif
}

void finishSwitch(void* fakeStack, const void** bottomOld, size_t* sizeOld) {
#if defined(SPECTRACE_FIBERS_UNDER_ASAN)
  __sanitizer_finish_switch_fiber(fakeStack, bottomOld, sizeOld);
#else
  (void)fakeStack, (void)bottomOld, (void)sizeOld;
#endif
}

// boost's guarded stack, noting where it lies for the switches above.
class NotedStack {
 public:
  explicit NotedStack(BeamFiber& beam) : beam_(&beam), stack_(kFiberStackBytes) {}
  boost::context::stack_context allocate() {
    boost::context::stack_context context = stack_.allocate();
    beam_->stackBottom = static_cast<const char*>(context.sp) - context.size;  // stacks grow down from sp
    beam_->stackSize = context.size;
    return context;
  }
  void deallocate(boost::context::stack_context& context) noexcept {
#if defined(SPECTRACE_FIBERS_UNDER_ASAN)
    // The frames' red zones stay marked in the shadow after the unmap, and
    // memory mapped there later (a film) would read as a stack overflow.
    __asan_unpoison_memory_region(static_cast<char*>(context.sp) - context.size, context.size);
#endif
    stack_.deallocate(context);
  }

 private:
  BeamFiber* beam_;
  boost::context::protected_fixedsize_stack stack_;
};

}  // namespace

struct FiberEntry {
  WalkInterleaver* owner;
  BeamFiber* beam;
  boost::context::fiber operator()(boost::context::fiber&& scheduler) const {
    finishSwitch(nullptr, &owner->threadStackBottom_, &owner->threadStackSize_);
    beam->scheduler = std::move(scheduler);
    beam->counted = owner->run_(beam->kernel);
    beam->finished = true;
    startSwitch(nullptr, owner->threadStackBottom_, owner->threadStackSize_);  // this stack is done with
    return std::move(beam->scheduler);
  }
};

WalkInterleaver::WalkInterleaver(const device::BeamKernel& kernel, size_t beamsInFlight,
                                 std::function<uint64_t(device::BeamKernel&)> run)
    : run_(std::move(run)) {
  fibers_.reserve(beamsInFlight);
  for (size_t i = 0; i < beamsInFlight; ++i) {
    BeamFiber& beam = fibers_.emplace_back(kernel, *this);
    beam.kernel.handedWalk = &beam.walk;
    beam.kernel.awaitWalk = &WalkInterleaver::awaitWalk;
    beam.kernel.awaitContext = &beam;
    beam.fiber = boost::context::fiber(std::allocator_arg, NotedStack(beam), FiberEntry{this, &beam});
  }
}

void WalkInterleaver::resume(BeamFiber& beam) {
  startSwitch(&threadFakeStack_, beam.stackBottom, beam.stackSize);
  beam.fiber = std::move(beam.fiber).resume();
  finishSwitch(threadFakeStack_, nullptr, nullptr);
}

void WalkInterleaver::awaitWalk(void* context) {
  BeamFiber& beam = *static_cast<BeamFiber*>(context);
  beam.walking = true;
  // The loop's stack, as the fiber entry noted it: every fiber of a thread
  // is resumed from the same loop.
  WalkInterleaver& owner = *beam.owner;
  startSwitch(&beam.savedFakeStack, owner.threadStackBottom_, owner.threadStackSize_);
  beam.scheduler = std::move(beam.scheduler).resume();
  finishSwitch(beam.savedFakeStack, &owner.threadStackBottom_, &owner.threadStackSize_);
}

uint64_t WalkInterleaver::counted() const {
  uint64_t total = 0;
  for (const BeamFiber& beam : fibers_) total += beam.counted;
  return total;
}

}  // namespace spectrace
