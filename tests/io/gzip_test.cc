// io/gzip.h: round trips, and damaged or oversized streams refused with one line.
#include "io/gzip.h"

#include <random>
#include <string>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

TEST(Gzip, RoundTripsAndCompressesRepetitiveBytes) {
  std::mt19937 rng(5);
  std::string noise(100000, '\0');
  for (char& c : noise) c = static_cast<char>(rng() & 0xff);
  for (const std::string& bytes : {std::string(), std::string("a"), std::string(1 << 20, 'x'), noise}) {
    std::string gz, back;
    ASSERT_TRUE(GzipCompress(bytes, &gz).ok());
    ASSERT_GE(gz.size(), 18u);  // Header and trailer.
    EXPECT_EQ(static_cast<unsigned char>(gz[0]), 0x1f);
    EXPECT_EQ(static_cast<unsigned char>(gz[1]), 0x8b);
    ASSERT_TRUE(GzipDecompress(gz, &back).ok());
    EXPECT_EQ(back, bytes);
  }
  std::string gz;
  ASSERT_TRUE(GzipCompress(std::string(1 << 20, 'x'), &gz).ok());
  EXPECT_LT(gz.size(), 5000u);
}

TEST(Gzip, RefusesDamagedTruncatedAndOversizedStreams) {
  std::string gz, back;
  ASSERT_TRUE(GzipCompress(std::string(100000, 'y') + "tail", &gz).ok());
  Status status = GzipDecompress(gz.substr(0, gz.size() / 2), &back);
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(status.message().find('\n'), std::string::npos);
  EXPECT_FALSE(GzipDecompress("not gzip at all", &back).ok());
  std::string damaged = gz;
  damaged[gz.size() - 6] ^= 0x55;  // The CRC.
  EXPECT_FALSE(GzipDecompress(damaged, &back).ok());
  status = GzipDecompress(gz, &back, 1000);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("more than 1000 bytes"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace mocapsolve
