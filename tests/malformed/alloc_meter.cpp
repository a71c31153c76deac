// Replaces the global operator new/delete with malloc/free plus accounting. Sizes come
// from malloc_usable_size, so delete needs no header (and ASan still checks each block).
#include "alloc_meter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

#include <malloc.h>

namespace {

std::atomic<std::size_t> live{0}, peak{0};

void* counted(void* p) {
    if (!p) throw std::bad_alloc();
    std::size_t now = live.fetch_add(malloc_usable_size(p)) + malloc_usable_size(p);
    for (std::size_t old = peak.load(); now > old && !peak.compare_exchange_weak(old, now);) {
    }
    return p;
}
void uncount(void* p) {
    if (!p) return;
    live.fetch_sub(malloc_usable_size(p));
    std::free(p);
}
void* aligned(std::size_t n, std::align_val_t a) {
    std::size_t al = std::size_t(a);
    return std::aligned_alloc(al, (n + al - 1) / al * al);
}

}  // namespace

namespace voxray::test::malformed {
std::size_t live_bytes() { return live.load(); }
std::size_t peak_bytes() { return peak.load(); }
void reset_peak() { peak.store(live.load()); }
}  // namespace voxray::test::malformed

void* operator new(std::size_t n) { return counted(std::malloc(n ? n : 1)); }
void* operator new[](std::size_t n) { return counted(std::malloc(n ? n : 1)); }
void* operator new(std::size_t n, std::align_val_t a) { return counted(aligned(n ? n : 1, a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return counted(aligned(n ? n : 1, a)); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
    try { return operator new(n); } catch (...) { return nullptr; }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
    try { return operator new[](n); } catch (...) { return nullptr; }
}
void operator delete(void* p) noexcept { uncount(p); }
void operator delete[](void* p) noexcept { uncount(p); }
void operator delete(void* p, std::size_t) noexcept { uncount(p); }
void operator delete[](void* p, std::size_t) noexcept { uncount(p); }
void operator delete(void* p, std::align_val_t) noexcept { uncount(p); }
void operator delete[](void* p, std::align_val_t) noexcept { uncount(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { uncount(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { uncount(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { uncount(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { uncount(p); }
