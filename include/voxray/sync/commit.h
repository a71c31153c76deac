/* The commit kernel, written once: copies the words of a commit packet
 * (sync/commit_layout.h) into the device copy of a structure blob. Compiled as OpenCL C
 * 1.2 (backends/opencl/kernels/entry.cl includes it), as GLSL (backends/vulkan/shaders/
 * commit.glsl) and as C++ (tests run it against the host packer).
 *
 * One work-item per data word: item i finds its record by binary search over the
 * records' ascending source offsets, then writes one word. Every item does the same
 * small amount of work whatever the mix of range sizes (thousands of one-word ranges or
 * one long run), so no lane idles, and no device limit on work-group counts per record
 * applies. The search costs log2(R) reads of a table that stays in cache.
 *
 * The blob is written here, so it needs a writable buffer type. The trace kernels read
 * through the read-only VX_BLOB of kernels/prelude.h, which lets compilers cache loads;
 * only this file writes, through VX_BLOB_RW:
 *   OpenCL: a __global uint*; GLSL: vx_words_rw, a buffer_reference declared without
 *   `readonly` in backends/vulkan/shaders/preamble.glsl; C++: std::uint32_t*.
 */
#include "voxray/kernels/prelude.h"
#include "voxray/sync/commit_layout.h"

#if defined(VX_DIALECT_OPENCL)
#define VX_BLOB_RW __global uint*
#define vx_store(b, i, v) ((b)[(i)] = (v))
#elif defined(VX_DIALECT_GLSL)
#define VX_BLOB_RW vx_words_rw
#define vx_store(b, i, v) ((b).w[(i)] = (v))
#else
#define VX_BLOB_RW std::uint32_t*
#define vx_store(b, i, v) ((b)[(i)] = (v))
#endif

/* Index of the record whose data holds packet data word i: the last record whose source
 * offset is <= i. Record 0 has source offset 0, so one always exists for i < N. */
VX_FN uint vx_commit_find(VX_BLOB packet, uint records, uint i) {
    uint table = vx_load(packet, VX_COMMIT_HEADER_TABLE);
    uint lo = 0u;
    uint hi = records - 1u;
    while (lo < hi) {
        uint mid = lo + (hi - lo + 1u) / 2u; /* rounds up: lo always advances */
        uint source = vx_load(packet, table + mid * VX_COMMIT_RECORD_WORDS + VX_COMMIT_RECORD_SOURCE);
        if (source <= i)
            lo = mid;
        else
            hi = mid - 1u;
    }
    return lo;
}

/* Work-item i of N (the packet's data word count): copies data word i into the blob.
 * Items at or past N, from rounding the dispatch up to whole groups, do nothing. */
VX_FN void vx_commit_word(VX_BLOB_RW blob, VX_BLOB packet, uint i) {
    uint records = vx_load(packet, VX_COMMIT_HEADER_RECORDS);
    if (i >= vx_load(packet, VX_COMMIT_HEADER_DATA_WORDS) || records == 0u) return;
    uint r = vx_commit_find(packet, records, i);
    uint record = vx_load(packet, VX_COMMIT_HEADER_TABLE) + r * VX_COMMIT_RECORD_WORDS;
    uint within = i - vx_load(packet, record + VX_COMMIT_RECORD_SOURCE);
    /* Always true for a well-formed packet; a malformed one must not write out of range. */
    if (within < vx_load(packet, record + VX_COMMIT_RECORD_COUNT)) {
        uint value = vx_load(packet, vx_load(packet, VX_COMMIT_HEADER_DATA) + i);
        vx_store(blob, vx_load(packet, record + VX_COMMIT_RECORD_DEST) + within, value);
    }
}
