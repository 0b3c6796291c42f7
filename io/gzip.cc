#include "io/gzip.h"

#include <zlib.h>

#include <algorithm>
#include <limits>
#include <utility>

namespace mocapsolve {

Status GzipCompress(const std::string& bytes, std::string* gz) {
  if (bytes.size() > std::numeric_limits<uInt>::max()) return Status::Error("gzip: input over 4 GB");
  z_stream stream{};
  // windowBits 15 + 16: a gzip header and trailer rather than zlib's.
  if (deflateInit2(&stream, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    return Status::Error("gzip: cannot start zlib");
  }
  std::string out(deflateBound(&stream, static_cast<uLong>(bytes.size())), '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  stream.avail_in = static_cast<uInt>(bytes.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = static_cast<uInt>(out.size());
  const int result = deflate(&stream, Z_FINISH);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  if (result != Z_STREAM_END) return Status::Error("gzip: zlib could not compress");
  *gz = std::move(out);
  return Status::Ok();
}

Status GzipDecompress(const std::string& gz, std::string* bytes, size_t max_bytes) {
  if (gz.size() > std::numeric_limits<uInt>::max()) return Status::Error("gzip: input over 4 GB");
  z_stream stream{};
  if (inflateInit2(&stream, 15 + 16) != Z_OK) return Status::Error("gzip: cannot start zlib");
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(gz.data()));
  stream.avail_in = static_cast<uInt>(gz.size());
  std::string out;
  int result = Z_OK;
  while (result == Z_OK) {
    const size_t done = out.size();
    const size_t grow = std::min<size_t>(std::max<size_t>(4 * gz.size(), 1 << 16), 1u << 30);
    if (done >= max_bytes) {
      inflateEnd(&stream);
      return Status::Error("gzip: inflates to more than " + std::to_string(max_bytes) + " bytes");
    }
    out.resize(std::min(done + grow, max_bytes));
    stream.next_out = reinterpret_cast<Bytef*>(out.data() + done);
    stream.avail_out = static_cast<uInt>(out.size() - done);
    result = inflate(&stream, Z_NO_FLUSH);
    out.resize(out.size() - stream.avail_out);
    if (result == Z_BUF_ERROR && stream.avail_out != 0) break;  // Input ended early.
    if (result == Z_BUF_ERROR) result = Z_OK;                     // Output full: grow.
  }
  inflateEnd(&stream);
  if (result != Z_STREAM_END) return Status::Error("gzip: damaged or truncated stream");
  *bytes = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
