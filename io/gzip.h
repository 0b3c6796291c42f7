// gzip (RFC 1952) through zlib, in memory: the `mocapsolve view` pages carry their binary
// arrays gzip-compressed (the browser inflates them natively with DecompressionStream),
// and tests read them back. Level 6 (zlib's default): a 10,000-frame take's page
// compresses at ~40 MB/s to about half its size (viewer/view_page.h).
#ifndef MOCAPSOLVE_IO_GZIP_H_
#define MOCAPSOLVE_IO_GZIP_H_

#include <cstddef>
#include <string>

#include "kinematics/status.h"

namespace mocapsolve {

// The gzip stream of `bytes` (inputs up to 4 GB).
Status GzipCompress(const std::string& bytes, std::string* gz);

// The bytes of a gzip stream; an error for a damaged stream or more than `max_bytes`.
Status GzipDecompress(const std::string& gz, std::string* bytes, size_t max_bytes = size_t{1} << 32);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_GZIP_H_
