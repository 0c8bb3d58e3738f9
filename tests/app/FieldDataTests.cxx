// The values after a header are exactly what the header declares, or the file is refused: NRRD
// files written by teem's `unu` (raw, gzip and ascii encodings, attached and detached, with byte
// and line skips) and MetaImage files written by VTK's writer (compressed or not, one file or a
// header and a data file), then cut, lengthened or relabelled as a damaged or mislabelled file
// would be. Each read either gives the known values voxel for voxel or a message that names the
// file and the sizes that disagree; none reads zeros or garbage where the data fall short.
#include "FieldTestFiles.h"
#include "KnownFieldFiles.h"

#include "SupportRun.h"

#include <gtest/gtest.h>
#include <vtkImageData.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <fstream>

namespace
{

using namespace cloudvis::support;
using namespace cloudvis::test;

// The error reading `path` gives; the test fails unless it contains every one of `parts`.
void ExpectRefused(const std::string& path, const std::vector<std::string>& parts)
{
  const std::string error = ErrorOf([&] { cloudvis::ReadField(path); });
  for (const std::string& part : parts)
  {
    EXPECT_NE(error.find(part), std::string::npos) << "\"" << part << "\" not in: " << error;
  }
}

std::string Replaced(std::string text, const std::string& from, const std::string& to)
{
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// ---- MetaImage ---------------------------------------------------------------------------------

// A .zraw cut in half read with exit 0 and half the voxels wrong; a header claiming more voxels
// than its stream holds read as zeros (at 1000^3 after allocating 4 GB).
TEST(MetaImage, CompressedDataAreCountedAgainstDimSize)
{
  TemporaryDirectory dir;
  const std::string path = WriteMetaImage(dir.File("z.mhd"), VTK_FLOAT, true);
  const std::string header = ReadText(path);
  const std::string stream = ReadText(dir.File("z.zraw"));
  ExpectKnownValues(cloudvis::ReadField(path));

  WriteText(dir.File("z.zraw"), stream.substr(0, stream.size() / 2));
  ExpectRefused(path, { "z.mhd (data file ", "z.zraw): the header states ", "truncated" });
  // Without CompressedDataSize (it is optional), the stream itself ends early.
  const std::string size = "CompressedDataSize = " + std::to_string(stream.size()) + "\n";
  WriteText(path, Replaced(header, size, ""));
  ExpectRefused(path,
    { "an image of 60 MET_FLOAT values: the compressed data end before their "
      "stream does after ",
      "of 240 bytes: the file is truncated" });
  WriteText(dir.File("z.zraw"), stream);
  ExpectKnownValues(cloudvis::ReadField(path));

  // More voxels than the stream can expand to: refused before anything of that size exists.
  WriteText(path, Replaced(header, "DimSize = 5 4 3", "DimSize = 1000 1000 1000"));
  ExpectRefused(path,
    { "an image of 1000000000 MET_FLOAT values is 4000000000 bytes, but its " +
      std::to_string(stream.size()) + " bytes of compressed data cannot decompress to more than" });
  // A little more, or less, than the stream holds.
  WriteText(path, Replaced(header, "DimSize = 5 4 3", "DimSize = 5 4 4"));
  ExpectRefused(path,
    { "an image of 80 MET_FLOAT values is 320 bytes, but the compressed data decompress to 240" });
  WriteText(path, Replaced(header, "DimSize = 5 4 3", "DimSize = 5 4 2"));
  ExpectRefused(path,
    { "an image of 40 MET_FLOAT values is 160 bytes, but the compressed data "
      "decompress to more" });
  // A corrupt stream (its zlib header's check bits broken).
  WriteText(path, header);
  std::string corrupt = stream;
  corrupt[1] = char(corrupt[1] ^ 0x01);
  WriteText(dir.File("z.zraw"), corrupt);
  ExpectRefused(path, { "the compressed data are corrupt (zlib: incorrect header check)" });

  // The same in one file (ElementDataFile = LOCAL).
  const std::string local = WriteMetaImage(dir.File("z.mha"), VTK_SHORT, true);
  ExpectKnownValues(cloudvis::ReadField(local));
  Truncate(local, ReadText(local).size() - 10);
  ExpectRefused(
    local, { "z.mha: the header states ", "bytes of compressed data but the file holds " });
}

// A data file longer than the header needs was read from its start, the rest ignored: the header
// or the file is wrong. MetaImage's HeaderSize says where the values start (-1: they end the file).
TEST(MetaImage, UncompressedDataMustBeWhatTheHeaderNeedsWhereItSays)
{
  TemporaryDirectory dir;
  const std::string local = WriteMetaImage(dir.File("u.mha"), VTK_FLOAT, false);
  WriteText(local, ReadText(local) + "extra bytes");
  ExpectRefused(local,
    { "u.mha: an image of 60 MET_FLOAT values needs 240 bytes of data after ",
      " bytes of header but the file holds 251: the sizes disagree" });

  const std::string path = WriteMetaImage(dir.File("u.mhd"), VTK_FLOAT, false);
  const std::string header = ReadText(path);
  WriteText(dir.File("u.raw"), std::string(16, '#') + ReadText(dir.File("u.raw")));
  ExpectRefused(path,
    { "(data file ",
      "u.raw): an image of 60 MET_FLOAT values needs 240 bytes "
      "of data but the file holds 256: the sizes disagree" });
  for (const char* headerSize : { "-1", "16" })
  {
    SCOPED_TRACE(headerSize);
    WriteText(path,
      Replaced(header,
        "ElementDataFile",
        std::string("HeaderSize = ") + headerSize + "\nElementDataFile"));
    ExpectKnownValues(cloudvis::ReadField(path));
  }
  // HeaderSize = 16 says where the values start, not that the file may go on after them.
  WriteText(dir.File("u.raw"), ReadText(dir.File("u.raw")) + "!");
  ExpectRefused(
    path, { "needs 240 bytes of data after 16 bytes of header but the file holds 241" });
}

// Every numeric ElementType in either byte order, as MetaIO sizes them (MET_LONG is 4 bytes): VTK's
// reader read MET_LONG as 8-byte values and crashed on MET_LONG_LONG ("malformed"). Other types
// are refused by name.
TEST(MetaImage, EveryNumericElementTypeIsReadAsFloat)
{
  TemporaryDirectory dir;
  const std::string path = WriteMetaImage(dir.File("t.mha"), VTK_FLOAT, false);
  const std::string text = ReadText(path);
  const std::string header = text.substr(0, text.size() - 240);
  struct Type
  {
    const char* Name;
    int Bytes;
    bool Signed;
    double Scale; // values index * Scale (- 30 when signed): the high bytes are used too
  };
  const Type types[] = { { "MET_CHAR", 1, true, 1 },
    { "MET_UCHAR", 1, false, 4 },
    { "MET_SHORT", 2, true, 500 },
    { "MET_USHORT", 2, false, 1000 },
    { "MET_INT", 4, true, 1 << 20 },
    { "MET_UINT", 4, false, 1 << 25 },
    { "MET_LONG", 4, true, 1 << 20 },
    { "MET_ULONG", 4, false, 1 << 25 },
    { "MET_LONG_LONG", 8, true, 8589934592.0 },
    { "MET_ULONG_LONG", 8, false, 17179869184.0 },
    { "MET_DOUBLE", 8, true, 0.5 } };
  for (const Type& type : types)
  {
    for (const bool bigEndian : { false, true })
    {
      SCOPED_TRACE(std::string(type.Name) + (bigEndian ? " big-endian" : " little-endian"));
      std::string values;
      for (int index = 0; index < 60; ++index)
      {
        const double value = (index - (type.Signed ? 30 : 0)) * type.Scale;
        unsigned char bytes[8];
        if (std::strcmp(type.Name, "MET_DOUBLE") == 0)
        {
          std::memcpy(bytes, &value, 8); // little-endian host
        }
        else
        {
          const auto word = std::uint64_t(std::int64_t(value));
          for (int b = 0; b < type.Bytes; ++b)
          {
            bytes[b] = static_cast<unsigned char>(word >> (8 * b));
          }
        }
        for (int b = 0; b < type.Bytes; ++b)
        {
          values += char(bytes[bigEndian ? type.Bytes - 1 - b : b]);
        }
      }
      std::string typed =
        Replaced(header, "ElementType = MET_FLOAT", std::string("ElementType = ") + type.Name);
      typed = Replaced(typed,
        "BinaryDataByteOrderMSB = False",
        std::string("BinaryDataByteOrderMSB = ") + (bigEndian ? "True" : "False"));
      WriteText(path, typed + values);
      cloudvis::FieldReport report;
      const auto field = cloudvis::ReadField(path, {}, &report);
      int wrong = 0;
      for (int index = 0; index < 60; ++index)
      {
        const double expected = float((index - (type.Signed ? 30 : 0)) * type.Scale);
        wrong += Density(field, index % 5, (index / 5) % 4, index / 20) == expected ? 0 : 1;
      }
      EXPECT_EQ(wrong, 0);
      EXPECT_EQ(Detail(report, "values"), std::string(type.Name) + ", converted to float");
    }
  }
  // Numbers written as text (BinaryData = False).
  std::string numbers;
  for (int index = 0; index < 60; ++index)
  {
    numbers += std::to_string(index) + (index % 10 == 9 ? "\n" : " ");
  }
  WriteText(path, Replaced(header, "BinaryData = True", "BinaryData = False") + numbers);
  EXPECT_EQ(Density(cloudvis::ReadField(path), 4, 3, 2), 59.0);
  WriteText(path, Replaced(header, "BinaryData = True", "BinaryData = False") + "1 2 3\n");
  ExpectRefused(path,
    { "an image of 60 MET_FLOAT values written as text needs at least 119 bytes (a digit and a "
      "separator per number) but the file holds 6 after its first " });
  WriteText(path,
    Replaced(header, "BinaryData = True", "BinaryData = False") + "1 2 3" + std::string(120, ' '));
  ExpectRefused(path, { "an image of 60 MET_FLOAT values: the text holds 3 numbers, not 60" });
  // Not numbers, or not one per voxel.
  WriteText(path, Replaced(header, "ElementType = MET_FLOAT", "ElementType = MET_STRING"));
  ExpectRefused(path,
    { "the MetaImage ElementType MET_STRING is not a numeric type cloudvis reads "
      "(it reads MET_CHAR, " });
  WriteText(path, Replaced(header, "ElementType = MET_FLOAT", "ElementType = MET_FLOAT_ARRAY"));
  ExpectRefused(
    path, { "MET_FLOAT_ARRAY holds vectors; a density field needs one value per voxel" });
}

// ---- NRRD --------------------------------------------------------------------------------------

std::string UnuSave(const std::string& input,
  const std::string& output,
  const std::string& encoding)
{
  return "teem-unu save -f nrrd -e " + encoding + " -i '" + input + "' -o '" + output +
    "' 2>/dev/null";
}

TEST(Nrrd, DataAreCheckedAgainstTheHeaderInEveryEncoding)
{
  TemporaryDirectory dir;
  const std::string raw = WriteKnownRaw(dir);
  RunTool(Unu(raw, dir.File("r.nrrd"), "-sp 1 1 1"));
  // gzip: the stream must decompress to exactly the declared values.
  const std::string gzip = dir.File("g.nrrd");
  RunTool(UnuSave(dir.File("r.nrrd"), gzip, "gzip"));
  cloudvis::FieldReport report;
  ExpectKnownValues(cloudvis::ReadField(gzip, {}, &report));
  EXPECT_EQ(Detail(report, "values"), "float (compressed)");
  const std::string zipped = ReadText(gzip);
  Truncate(gzip, zipped.size() - 20);
  ExpectRefused(gzip,
    { "g.nrrd: an image of 60 float values: the compressed data end before "
      "their stream does" });
  WriteText(gzip, Replaced(zipped, "sizes: 5 4 3", "sizes: 5 4 2"));
  ExpectRefused(gzip,
    { "an image of 40 float values is 160 bytes, but the compressed data "
      "decompress to more" });
  // raw, attached: nothing may follow the values.
  WriteText(dir.File("r.nrrd"), ReadText(dir.File("r.nrrd")) + "\n\n");
  ExpectRefused(
    dir.File("r.nrrd"), { "needs 240 bytes of data after ", "holds 242: the sizes disagree" });
  // ascii: exactly 60 numbers.
  const std::string ascii = dir.File("a.nrrd");
  RunTool(Unu(raw, dir.File("r.nrrd"), "-sp 1 1 1"));
  RunTool(UnuSave(dir.File("r.nrrd"), ascii, "ascii"));
  ExpectKnownValues(cloudvis::ReadField(ascii));
  const std::string text = ReadText(ascii);
  WriteText(ascii, text.substr(0, text.rfind(" 232")) + "\n");
  ExpectRefused(
    ascii, { "a.nrrd: an image of 60 float values: the text holds 57 numbers, not 60" });
  WriteText(ascii, text + "60\n");
  ExpectRefused(ascii, { "the text holds more than 60 numbers" });
}

// A detached header's byte and line skips say where the values start in the data file; without
// them, a data file longer than the values is refused. (VTK's reader refused every skip.)
TEST(Nrrd, ByteAndLineSkipsSayWhereTheValuesStart)
{
  TemporaryDirectory dir;
  const std::string known = ReadText(WriteKnownRaw(dir));
  WriteText(dir.File("skip.raw"), "a first line\nand a second\n0123456789abcdef" + known);
  const std::string in = "cd '" + dir.Path + "' && ";
  RunTool(in + Unu("skip.raw", "lines.nhdr", "-h -ls 2 -bs 16"));
  RunTool(in + Unu("skip.raw", "end.nhdr", "-h -bs -1"));
  RunTool(in + Unu("skip.raw", "none.nhdr", "-h"));
  ExpectKnownValues(cloudvis::ReadField(dir.File("lines.nhdr")));
  ExpectKnownValues(cloudvis::ReadField(dir.File("end.nhdr")));
  ExpectRefused(dir.File("none.nhdr"),
    { "none.nhdr (data file ",
      "skip.raw): an image of 60 float values needs 240 bytes of data but "
      "the file holds 282: the sizes disagree" });
  // gzip: the byte skip counts decompressed bytes (teem's rule), the line skip the file's.
  RunTool("cd '" + dir.Path + "' && gzip -k skip.raw");
  RunTool(in +
    "teem-unu make -h -i skip.raw.gz -t float -s 5 4 3 -en little -e gzip -bs 42 -o "
    "zipped.nhdr 2>/dev/null");
  ExpectKnownValues(cloudvis::ReadField(dir.File("zipped.nhdr")));
  // A byte skip beyond the data.
  RunTool(in + Unu("skip.raw", "far.nhdr", "-h -bs 100"));
  ExpectRefused(dir.File("far.nhdr"),
    { "needs 240 bytes of data after 100 bytes of header but the "
      "file holds 182: it is truncated" });
}

// ---- Every encoding ----------------------------------------------------------------------------

// The error reading `path` gives in a child process whose address space may grow by only 1 GiB
// more, or what became of the child: a read that allocates the declared size before checking it
// against the data dies of it there (bad_alloc, or VTK's failed allocation written through).
std::string ErrorWithin1GiB(const std::string& path)
{
  int channel[2];
  if (::pipe(channel) != 0)
  {
    return "no pipe";
  }
  const pid_t child = ::fork();
  if (child == 0)
  {
    ::close(channel[0]);
    std::uint64_t pages = 0;
    std::ifstream("/proc/self/statm") >> pages; // the address space's size now
    const rlim_t limit = rlim_t(pages * std::uint64_t(::sysconf(_SC_PAGESIZE)) + (1ull << 30));
    const rlimit memory{ limit, limit };
    ::setrlimit(RLIMIT_AS, &memory);
    std::string message = "no InputError";
    try
    {
      cloudvis::ReadField(path);
    }
    catch (const cloudvis::InputError& e)
    {
      message = e.what();
    }
    catch (const std::exception& e)
    {
      message = std::string("not an InputError: ") + e.what();
    }
    const ssize_t written = ::write(channel[1], message.data(), message.size());
    ::_exit(written == ssize_t(message.size()) ? 0 : 1);
  }
  ::close(channel[1]);
  std::string message;
  char buffer[4096];
  for (ssize_t n; (n = ::read(channel[0], buffer, sizeof buffer)) > 0;)
  {
    message.append(buffer, std::size_t(n));
  }
  ::close(channel[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  if (WIFSIGNALED(status))
  {
    return "the read died of signal " + std::to_string(WTERMSIG(status));
  }
  return message;
}

// A header declaring 1000^3 values (4 GB as float, within the default field.max_voxels of
// 1024^3) beside a few bytes of data is refused by the sizes before anything of the declared size
// is allocated, in every encoding: before, a 129-byte .zraw or a 10-byte ascii NRRD cost 4 GB (and
// with less memory than that, the read died instead of naming the sizes).
TEST(FieldData, HugeDeclaredSizesBesideLittleDataAreRefusedBeforeAllocation)
{
  TemporaryDirectory dir;
  const std::string raw = WriteKnownRaw(dir);
  RunTool(Unu(raw, dir.File("r.nrrd"), "-sp 1 1 1"));
  RunTool(UnuSave(dir.File("r.nrrd"), dir.File("g.nrrd"), "gzip"));
  RunTool(UnuSave(dir.File("r.nrrd"), dir.File("a.nrrd"), "ascii"));
  const std::string huge = "sizes: 1000 1000 1000";
  for (const char* name : { "r.nrrd", "g.nrrd", "a.nrrd" })
  {
    WriteText(dir.File(name), Replaced(ReadText(dir.File(name)), "sizes: 5 4 3", huge));
  }
  const std::string mhd = WriteMetaImage(dir.File("z.mhd"), VTK_FLOAT, true);
  WriteText(mhd, Replaced(ReadText(mhd), "DimSize = 5 4 3", "DimSize = 1000 1000 1000"));
  const std::string text = WriteMetaImage(dir.File("t.mha"), VTK_FLOAT, false);
  const std::string binary = ReadText(text);
  const std::string header = binary.substr(0, binary.size() - 240); // the 60 floats end the file
  WriteText(text,
    Replaced(Replaced(header, "DimSize = 5 4 3", "DimSize = 1000 1000 1000"),
      "BinaryData = True",
      "BinaryData = False") +
      "1 2 3\n");
  const std::pair<std::string, std::string> cases[] = {
    { dir.File("r.nrrd"), "an image of 1000000000 float values needs 4000000000 bytes of data" },
    { dir.File("g.nrrd"), "an image of 1000000000 float values is 4000000000 bytes, but its " },
    { mhd, "an image of 1000000000 MET_FLOAT values is 4000000000 bytes, but its " },
    { dir.File("a.nrrd"),
      "an image of 1000000000 float values written as text needs at least 1999999999 bytes" },
    { text,
      "an image of 1000000000 MET_FLOAT values written as text needs at least 1999999999 "
      "bytes (a digit and a separator per number) but the file holds 6" },
  };
  for (const auto& [path, expected] : cases)
  {
    SCOPED_TRACE(path);
    const std::string error = ErrorWithin1GiB(path);
    EXPECT_NE(error.find(expected), std::string::npos) << error;
    EXPECT_EQ(error.find("memory"), std::string::npos) << error;
  }
}

} // namespace
