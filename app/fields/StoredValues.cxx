// The voxel values that follow a header, decoded by cloudvis itself for every format whose header
// it parses (raw volumes, NRRD, MetaImage): raw bytes, a zlib or gzip stream, or numbers written
// as text, in any of RawTypes(), either byte order, converted to float block by block.
//
// Why here and not in a library: a header states how many values there are, and the data must
// hold exactly that many. VTK's readers do not check it (vtkMetaImageReader read half a truncated
// .zraw as garbage, and a header claiming 1000^3 voxels beside a 57-byte stream as a billion zeros;
// vtkNrrdReader's text reading fills what is missing with zeros), nor do they know every type
// (vtkMetaImageReader corrupted the heap on MET_LONG_LONG). So the data are counted as they are
// decoded: a stream that ends early, is corrupt, or yields more than declared is refused, and so
// is a data region longer or shorter than the values need. Nothing of the declared size is
// allocated before the declared size has been checked against field.max_voxels and memory (the
// callers' CheckFieldSize) and against what the data region can hold (CheckRegion): exactly the
// bytes of raw values, at most deflate's 1032:1 expansion of a compressed stream, at least a
// character and a separator per number of text.
#include "FieldFormatReaders.h"

#include "InputFiles.h"

#include <vtkFloatArray.h>

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>

namespace cloudvis
{
namespace
{

// Values decoded per block: the bytes of a block are never held whole beside the floats.
constexpr std::uint64_t BlockValues = std::uint64_t(1) << 20;

// The most deflate expands: 258 bytes from each pair of 1-bit codes, about 1032:1 (zlib's
// technical notes); the stream's header, trailer and block headers only lower it.
constexpr double MaximumInflation = 1032.0;

// Value `i` of a block of raw bytes, as a double.
template<typename T>
double RawValue(const unsigned char* bytes, bool swap)
{
  unsigned char copy[sizeof(T)];
  for (std::size_t b = 0; b < sizeof(T); ++b)
  {
    copy[b] = bytes[swap ? sizeof(T) - 1 - b : b];
  }
  T value;
  std::memcpy(&value, copy, sizeof(T));
  return double(value);
}

double (*RawDecoder(int vtkType))(const unsigned char*, bool)
{
  switch (vtkType)
  {
    case VTK_UNSIGNED_CHAR:
      return RawValue<std::uint8_t>;
    case VTK_SIGNED_CHAR:
      return RawValue<std::int8_t>;
    case VTK_UNSIGNED_SHORT:
      return RawValue<std::uint16_t>;
    case VTK_SHORT:
      return RawValue<std::int16_t>;
    case VTK_UNSIGNED_INT:
      return RawValue<std::uint32_t>;
    case VTK_INT:
      return RawValue<std::int32_t>;
    case VTK_TYPE_UINT64:
      return RawValue<std::uint64_t>;
    case VTK_TYPE_INT64:
      return RawValue<std::int64_t>;
    case VTK_DOUBLE:
      return RawValue<double>;
    default:
      return RawValue<float>;
  }
}

bool LittleEndianHost()
{
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

std::string Count(double value)
{
  std::ostringstream text;
  text.precision(15);
  text << value;
  return text.str();
}

// Fills the float array from whole values, counting those beyond float's range.
class FloatSink
{
public:
  FloatSink(const StoredValues& stored, std::uint64_t count)
    : Total(count)
    , Decode(RawDecoder(stored.Type->VtkType))
    , Bytes(std::uint64_t(stored.Type->Bytes))
    , Swap(stored.Type->Bytes > 1 && stored.BigEndian == LittleEndianHost())
  {
    this->Values = vtkSmartPointer<vtkFloatArray>::New();
    this->Values->SetName("density");
    this->Values->SetNumberOfTuples(vtkIdType(count));
    this->Out = this->Values->GetPointer(0);
  }

  // Decodes `values` whole values from `bytes` (the caller never passes more than remain).
  void Binary(const unsigned char* bytes, std::uint64_t values)
  {
    for (std::uint64_t i = 0; i < values; ++i)
    {
      this->Number(this->Decode(bytes + i * this->Bytes, this->Swap));
    }
  }

  void Number(double value)
  {
    this->Beyond += BeyondFloat(value) ? 1 : 0;
    this->Out[this->Done++] = float(value);
  }

  std::uint64_t Done = 0;
  std::uint64_t Beyond = 0;
  const std::uint64_t Total;
  vtkSmartPointer<vtkFloatArray> Values;

private:
  double (*Decode)(const unsigned char*, bool);
  const std::uint64_t Bytes;
  const bool Swap;
  float* Out = nullptr;
};

// The checks every encoding's data region must pass before the `count` values are allocated:
// the region can hold them (raw: exactly, or ending with them when `AtEnd`; compressed: no more
// than deflate's largest expansion of its bytes; text: one character and one separator per
// number at the least). A header declaring a billion values beside a few bytes is refused here,
// by sizes, not by running out of memory.
void CheckRegion(const std::string& path,
  const StoredValues& stored,
  std::uint64_t regionBytes,
  std::uint64_t count,
  const std::string& what)
{
  const double values = double(count);
  switch (stored.Encoding)
  {
    case ValueEncoding::Raw:
    {
      const double needed = values * stored.Type->Bytes;
      CheckFileHoldsData(path, regionBytes + stored.Offset, stored.Offset, needed, what);
      if (!stored.AtEnd && double(regionBytes) > needed)
      {
        std::ostringstream text;
        text << what << " needs " << Count(needed) << " bytes of data";
        if (stored.Offset > 0)
        {
          text << " after " << stored.Offset << " bytes of header";
        }
        text << " but the file holds " << regionBytes
             << ": the sizes disagree, so its header or the file is wrong";
        Fail(path, text.str());
      }
      break;
    }
    case ValueEncoding::Zlib:
    {
      const double declared = double(stored.SkipDecoded) + values * stored.Type->Bytes;
      if (declared > (double(regionBytes) + 1.0) * MaximumInflation)
      {
        Fail(path,
          what + " is " + Count(declared) + " bytes, but its " + std::to_string(regionBytes) +
            " bytes of compressed data cannot decompress to more than " +
            Count(double(regionBytes) * MaximumInflation) +
            " (zlib expands at most about 1032:1): the file is truncated or its header is wrong");
      }
      break;
    }
    case ValueEncoding::Text:
    {
      const double needed = count > 0 ? 2.0 * values - 1.0 : 0.0;
      if (double(regionBytes) < needed)
      {
        Fail(path,
          what + " written as text needs at least " + Count(needed) +
            " bytes (a digit and a separator per number) but the file holds " +
            std::to_string(regionBytes) +
            (stored.Offset > 0 ? " after its first " + std::to_string(stored.Offset) + " bytes"
                               : "") +
            ": it is truncated or its header is wrong");
      }
      break;
    }
  }
}

// Raw bytes: the region holds exactly the values (or ends with them: `AtEnd`), as CheckRegion
// made sure.
void ReadRaw(const std::string& path,
  const RegularInputFile& file,
  const StoredValues& stored,
  std::uint64_t regionBytes,
  FloatSink& sink)
{
  std::uint64_t at = stored.Offset;
  if (stored.AtEnd)
  {
    at += regionBytes - sink.Total * std::uint64_t(stored.Type->Bytes); // bytes before skipped
  }
  const std::uint64_t bytes = std::uint64_t(stored.Type->Bytes);
  for (std::uint64_t first = 0; first < sink.Total; first += BlockValues)
  {
    const std::uint64_t count = std::min(BlockValues, sink.Total - first);
    const std::string block = file.ReadAt(at + first * bytes, std::size_t(count * bytes));
    if (block.size() != count * bytes)
    {
      Fail(path, "the file became shorter while it was read");
    }
    sink.Binary(reinterpret_cast<const unsigned char*>(block.data()), count);
  }
}

// A zlib or gzip stream (zlib's automatic detection) that must decompress to exactly the
// declared bytes, using every byte of the region (CheckRegion has bounded its expansion).
void ReadCompressed(const std::string& path,
  const RegularInputFile& file,
  const StoredValues& stored,
  std::uint64_t regionBytes,
  FloatSink& sink,
  const std::string& what)
{
  const std::uint64_t valueBytes = std::uint64_t(stored.Type->Bytes);
  const double declared = double(stored.SkipDecoded) + double(sink.Total) * valueBytes;
  z_stream stream{};
  if (inflateInit2(&stream, 15 + 32) != Z_OK) // 15: the largest window; +32: zlib or gzip
  {
    Fail(path, "cannot start zlib's decompression");
  }
  struct End
  {
    z_stream* Stream;
    ~End() { inflateEnd(this->Stream); }
  } end{ &stream };

  const std::uint64_t inputBlock = std::uint64_t(1) << 20;
  std::string input;
  std::uint64_t consumed = 0; // bytes of the region handed to zlib
  std::string output(std::size_t(BlockValues * valueBytes), '\0');
  std::uint64_t produced = 0; // decompressed bytes so far
  std::uint64_t skip = stored.SkipDecoded;
  std::size_t pending = 0; // bytes of `output` not yet decoded (a partial value)
  const auto progress = [&]
  { return " after " + Count(double(produced)) + " of " + Count(declared) + " bytes"; };
  bool ended = false;
  while (!ended)
  {
    if (stream.avail_in == 0 && consumed < regionBytes)
    {
      input = file.ReadAt(
        stored.Offset + consumed, std::size_t(std::min(inputBlock, regionBytes - consumed)));
      if (input.empty())
      {
        Fail(path, "the file became shorter while it was read");
      }
      consumed += input.size();
      stream.next_in = reinterpret_cast<Bytef*>(&input[0]);
      stream.avail_in = uInt(input.size());
    }
    stream.next_out = reinterpret_cast<Bytef*>(&output[pending]);
    stream.avail_out = uInt(output.size() - pending);
    const int status = inflate(&stream, Z_NO_FLUSH);
    const std::size_t filled = output.size() - pending - stream.avail_out;
    produced += filled;
    if (status == Z_STREAM_END)
    {
      ended = true;
    }
    else if (status == Z_BUF_ERROR && stream.avail_in == 0 && consumed == regionBytes)
    {
      Fail(path,
        what + ": the compressed data end before their stream does" + progress() +
          ": the file is truncated");
    }
    else if (status != Z_OK && status != Z_BUF_ERROR)
    {
      Fail(path,
        what + ": the compressed data are corrupt (zlib: " +
          (stream.msg ? std::string(stream.msg) : "error " + std::to_string(status)) + ")" +
          progress());
    }
    if (double(produced) > declared)
    {
      Fail(path,
        what + " is " + Count(declared) +
          " bytes, but the compressed data decompress to more: the header or the file is wrong");
    }
    // Decode the whole values now in `output`; keep a partial one for the next round.
    std::size_t available = pending + filled;
    std::size_t begin = 0;
    const std::size_t skipped = std::size_t(std::min<std::uint64_t>(skip, available));
    skip -= skipped;
    begin += skipped;
    const std::uint64_t values = (available - begin) / valueBytes;
    sink.Binary(reinterpret_cast<const unsigned char*>(output.data()) + begin, values);
    begin += std::size_t(values * valueBytes);
    pending = available - begin;
    std::memmove(&output[0], output.data() + begin, pending);
  }
  if (double(produced) < declared)
  {
    Fail(path,
      what + " is " + Count(declared) + " bytes, but the compressed data decompress to " +
        Count(double(produced)) + ": the file is truncated or its header is wrong");
  }
  const std::uint64_t unused = regionBytes - consumed + stream.avail_in;
  if (unused > 0)
  {
    Fail(path,
      what + ": " + std::to_string(unused) +
        " bytes follow the end of the compressed data: the sizes disagree, so its header or the "
        "file is wrong");
  }
}

// Numbers written as text, separated by white space (or commas): exactly as many as declared.
void ReadText(const std::string& path,
  const RegularInputFile& file,
  const StoredValues& stored,
  std::uint64_t regionBytes,
  FloatSink& sink,
  const std::string& what)
{
  const auto separator = [](char c)
  { return c == ',' || std::isspace(static_cast<unsigned char>(c)); };
  const std::uint64_t block = std::uint64_t(1) << 20;
  std::string token;
  const auto number = [&]
  {
    if (token.empty())
    {
      return;
    }
    if (sink.Done == sink.Total)
    {
      Fail(path,
        what + ": the text holds more than " + std::to_string(sink.Total) +
          " numbers: the sizes disagree, so its header or the file is wrong");
    }
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (*end != '\0' || token.size() > 64)
    {
      Fail(path,
        what + ": value " + std::to_string(sink.Done) + " is not a number (\"" +
          token.substr(0, 40) + "\")");
    }
    sink.Number(value);
    token.clear();
  };
  for (std::uint64_t at = 0; at < regionBytes; at += block)
  {
    const std::string text =
      file.ReadAt(stored.Offset + at, std::size_t(std::min(block, regionBytes - at)));
    if (text.empty())
    {
      Fail(path, "the file became shorter while it was read");
    }
    for (char c : text)
    {
      if (separator(c))
      {
        number();
      }
      else if (token.size() <= 64)
      {
        token += c;
      }
    }
  }
  number();
  if (sink.Done < sink.Total)
  {
    Fail(path,
      what + ": the text holds " + std::to_string(sink.Done) + " numbers, not " +
        std::to_string(sink.Total) + ": the file is truncated or its header is wrong");
  }
}

} // namespace

vtkSmartPointer<vtkFloatArray> ReadStoredValues(const std::string& path,
  const RegularInputFile& file,
  const StoredValues& stored,
  std::uint64_t count,
  const std::string& what)
{
  if (stored.Offset > file.Size())
  {
    Fail(path,
      "the data start at byte " + std::to_string(stored.Offset) + " but the file holds " +
        std::to_string(file.Size()) + ": it is truncated or its header is wrong");
  }
  const std::uint64_t toEnd = file.Size() - stored.Offset;
  if (stored.Length && *stored.Length != toEnd)
  {
    Fail(path,
      "the header states " + std::to_string(*stored.Length) + " bytes of " +
        (stored.Encoding == ValueEncoding::Zlib ? "compressed " : "") + "data but the file holds " +
        std::to_string(toEnd) +
        (stored.Offset > 0 ? " after its first " + std::to_string(stored.Offset) + " bytes" : "") +
        ": " +
        (*stored.Length > toEnd ? "it is truncated or its header is wrong"
                                : "the sizes disagree, so its header or the file is wrong"));
  }
  CheckRegion(path, stored, toEnd, count, what);
  FloatSink sink(stored, count);
  switch (stored.Encoding)
  {
    case ValueEncoding::Raw:
      ReadRaw(path, file, stored, toEnd, sink);
      break;
    case ValueEncoding::Zlib:
      ReadCompressed(path, file, stored, toEnd, sink, what);
      break;
    case ValueEncoding::Text:
      ReadText(path, file, stored, toEnd, sink, what);
      break;
  }
  RefuseBeyondFloat(path, "the file", sink.Beyond);
  return sink.Values;
}

} // namespace cloudvis
