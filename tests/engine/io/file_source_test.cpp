#include "engine/io/file_source.h"

#include <gtest/gtest.h>

#include "tests/support/temp_directory.h"

namespace plumb::io {
namespace {

TEST(FileSource, ReadsLinesWithNumbersAndOffsets) {
  test::TempDirectory dir;
  FileSource source(dir.write("lines.txt", "first\r\nsecond\n\nlast"));
  std::string line;
  ASSERT_TRUE(source.readLine(line));
  EXPECT_EQ(line, "first");
  EXPECT_EQ(source.offset(), 7u);
  ASSERT_TRUE(source.readLine(line));
  EXPECT_EQ(line, "second");
  ASSERT_TRUE(source.readLine(line));
  EXPECT_EQ(line, "");
  ASSERT_TRUE(source.readLine(line));
  EXPECT_EQ(line, "last");
  EXPECT_EQ(source.lineNumber(), 4u);
  EXPECT_FALSE(source.readLine(line));
  EXPECT_NE(std::string(source.errorAtLine("bad").what()).find("line 4: bad"), std::string::npos);
}

TEST(FileSource, ReadExactlyAcrossTheBufferAndReportsTruncation) {
  test::TempDirectory dir;
  std::string data(8 << 20, '\0');  // two buffers, and less than three chunks
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<char>(i * 7);
  FileSource source(dir.write("data.bin", data));
  std::vector<std::byte> chunk(3 << 20);
  source.readExactly(chunk, "a chunk");
  source.readExactly(chunk, "a chunk");
  EXPECT_EQ(static_cast<char>(chunk.back()), data[(6 << 20) - 1]);
  try {
    source.readExactly(chunk, "the third chunk");
    FAIL() << "expected a truncation error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("at byte 6291456"), std::string::npos) << message;
    EXPECT_NE(message.find("truncated"), std::string::npos) << message;
    EXPECT_NE(message.find("the third chunk"), std::string::npos) << message;
  }
}

TEST(FileSource, MissingFileAndDirectoryAreErrors) {
  test::TempDirectory dir;
  EXPECT_THROW(FileSource(dir.file("absent.ply")), Error);
  EXPECT_THROW(FileSource(dir.path().string()), Error);
}

TEST(FileSource, OverlongLinesAreAnError) {
  test::TempDirectory dir;
  FileSource source(dir.write("long.txt", std::string(5000, 'x')));
  std::string line;
  EXPECT_THROW(source.readLine(line, 1000), Error);
}

}  // namespace
}  // namespace plumb::io
