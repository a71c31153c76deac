/* The commit packet: what an incremental device update sends in ONE transfer. The host
 * (sync/commit_packet.hpp) packs the changed words of a structure blob behind a small
 * table saying where each run of words belongs; the commit kernel (sync/commit.h)
 * then scatters them into the device copy of the blob. One transfer plus one small
 * kernel replaces one transfer per dirty range: per-transfer overhead, not bandwidth,
 * is what makes many small copies slow.
 *
 *  packet (32-bit words)
 *  +------------------------------+ word 0
 *  | header (4 words)             |  record count R, data word count N,
 *  |                              |  table offset (= 4), data offset (= 4 + 3R)
 *  +------------------------------+ VX_COMMIT_HEADER_WORDS
 *  | records: R x 3 words         |  destination offset in the blob, word count,
 *  |                              |  source offset within the data (a running sum, so
 *  |                              |  ascending: the kernel binary-searches it)
 *  +------------------------------+ data offset
 *  | data: N words                |  the records' words, back to back, in record order
 *  +------------------------------+
 *
 * Records are sorted by destination and never overlap (the host merges ranges), so
 * every blob word is written by at most one work-item.
 */
#ifndef VOXRAY_LAYOUT_COMMIT_LAYOUT_H
#define VOXRAY_LAYOUT_COMMIT_LAYOUT_H

#define VX_COMMIT_HEADER_RECORDS 0
#define VX_COMMIT_HEADER_DATA_WORDS 1
#define VX_COMMIT_HEADER_TABLE 2
#define VX_COMMIT_HEADER_DATA 3
#define VX_COMMIT_HEADER_WORDS 4

#define VX_COMMIT_RECORD_DEST 0
#define VX_COMMIT_RECORD_COUNT 1
#define VX_COMMIT_RECORD_SOURCE 2
#define VX_COMMIT_RECORD_WORDS 3

#endif
