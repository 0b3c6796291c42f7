#include "io/content_hash.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <memory>

#include "io/atomic_file.h"

namespace mocapsolve {

void Fnv1a64::Update(std::string_view bytes) {
  uint64_t h = hash_;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  hash_ = h;
}

std::string HexHash(uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

Status HashFile(const std::string& path, uint64_t* hash) {
  int fd = -1;
  struct stat st;
  Status status = OpenRegularFile(path, &fd, &st);
  if (!status.ok()) return status;
  constexpr size_t kChunk = 1 << 20;
  std::unique_ptr<char[]> buffer(new char[kChunk]);
  Fnv1a64 fnv;
  while (true) {
    const ssize_t n = ::read(fd, buffer.get(), kChunk);
    if (n < 0) {
      ::close(fd);
      return Status::Error(path + ": cannot read the file");
    }
    if (n == 0) break;
    fnv.Update(std::string_view(buffer.get(), static_cast<size_t>(n)));
  }
  ::close(fd);
  *hash = fnv.value();
  return Status::Ok();
}

}  // namespace mocapsolve
