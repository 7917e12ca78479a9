#include <pcl_crf/logs/rosbag_structure.h>
#include <pcl_crf/io/readable_file.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace pcl_crf {
namespace {

// Record kinds (the header's "op" field) of the ROS bag v2.0 format.
constexpr std::uint8_t kMessageData = 0x02, kBagHeader = 0x03, kIndexData = 0x04, kChunk = 0x05,
                       kChunkInfo = 0x06, kConnection = 0x07;

/** One record: its header fields, and where it and its data lie. */
struct Record
{
  std::uint64_t at = 0;
  std::map<std::string, std::string> fields;
  std::uint64_t data_at = 0, data_size = 0;

  std::uint64_t
  end () const
  {
    return data_at + data_size;
  }
};

/** A span of the bag file: the whole file, or one chunk's data (\c base: the file offset
 *  of its first byte; \c size: its length, the chunk's uncompressed size). */
struct Bytes
{
  std::uint64_t base = 0, size = 0;
  bool chunk = false;
};

class BagChecker
{
public:
  BagChecker (const std::string& path, const std::vector<std::string>& topics)
  : path_ (path), topics_ (topics.begin (), topics.end ()), file_ (path, std::ios::binary),
    bag_{0, std::filesystem::file_size (path), false}
  {}

  void
  check ()
  {
    if (bag_.size < 13 || read (bag_, 0, 13) != "#ROSBAG V2.0\n")
      return;  // another version, or not a bag: librosbag says which
    const Index index = bagHeader ();
    std::uint64_t at = index.pos;
    for (std::uint32_t k = 0; k < index.connections; ++k) {
      const Record connection = record (bag_, at, kConnection, "connection");
      const std::uint32_t id = number<std::uint32_t> (connection, "conn");
      const auto topic = connection.fields.find ("topic");
      if (topic != connection.fields.end () && topics_.count (topic->second))
        read_connections_.insert (id);
      at = connection.end ();
    }
    for (std::uint32_t k = 0; k < index.chunks; ++k)
      at = checkChunkInfo (at, index);
  }

private:
  /** Where the bag header says its index lies, and what it holds. */
  struct Index
  {
    std::uint64_t chunks_begin = 0, pos = 0;
    std::uint32_t connections = 0, chunks = 0;
  };

  Index
  bagHeader ()
  {
    const Record header = record (bag_, 13, kBagHeader, "bag header");
    Index index;
    index.chunks_begin = header.end ();
    index.pos = number<std::uint64_t> (header, "index_pos");
    index.connections = number<std::uint32_t> (header, "conn_count");
    index.chunks = number<std::uint32_t> (header, "chunk_count");
    if (index.pos == 0)
      fail (13, "the bag has no index (index_pos 0: was its recording cut short? 'rosbag reindex' rebuilds it)");
    if (index.pos < index.chunks_begin || index.pos >= bag_.size)
      fail (13, "index_pos " + std::to_string (index.pos) + " lies outside the records (bytes " +
                    std::to_string (index.chunks_begin) + " to " + std::to_string (bag_.size) + ")");
    if ((std::uint64_t{index.connections} + index.chunks) * 8 > bag_.size - index.pos)
      fail (13, std::to_string (index.connections) + " connection and " + std::to_string (index.chunks) +
                    " chunk-info records cannot fit in the " + std::to_string (bag_.size - index.pos) +
                    " bytes after index_pos");
    return index;
  }

  /** The chunk info at \a at and the chunk it points to; returns where the next record starts. */
  std::uint64_t
  checkChunkInfo (std::uint64_t at, const Index& index)
  {
    const Record info = record (bag_, at, kChunkInfo, "chunk info");
    const std::uint64_t chunk_pos = number<std::uint64_t> (info, "chunk_pos");
    const std::uint32_t count = number<std::uint32_t> (info, "count");
    if (info.data_size != 8ull * count)
      fail (at, "a chunk info of " + std::to_string (count) + " connections holds " +
                    std::to_string (info.data_size) + " bytes, not 8 per connection");
    if (chunk_pos < index.chunks_begin || chunk_pos >= index.pos)
      fail (at, "chunk_pos " + std::to_string (chunk_pos) + " lies outside the chunks (bytes " +
                    std::to_string (index.chunks_begin) + " to " + std::to_string (index.pos) + ")");
    checkChunk (chunk_pos, count);
    return info.end ();
  }

  [[noreturn]] void
  fail (std::uint64_t at, const std::string& problem) const
  {
    throw LogError (path_ + ": not a readable ROS bag (truncated or corrupted?): at byte " + std::to_string (at) +
                    ", " + problem);
  }

  /** Bytes [at, at + count) of \a bytes; fails when they run past its end. A chunk's
   *  messages are read from its data, read whole once. */
  std::string
  read (const Bytes& bytes, std::uint64_t at, std::uint64_t count, std::uint64_t record = 0)
  {
    if (at > bytes.size || count > bytes.size - at)
      fail (bytes.base + record, "the record runs past the end of the " + std::string (bytes.chunk ? "chunk" : "file") +
                                     " (" + std::to_string (bytes.size) + " bytes)");
    if (bytes.chunk && chunk_at_ != bytes.base) {
      chunk_ = read (bag_, bytes.base, bytes.size);
      chunk_at_ = bytes.base;
    }
    if (bytes.chunk)
      return chunk_.substr (at, count);
    std::string text (count, '\0');
    file_.seekg (static_cast<std::streamoff> (at));
    if (count > 0 && !file_.read (&text[0], static_cast<std::streamsize> (count)))
      fail (at, "the file could not be read there");
    return text;
  }

  static std::uint32_t
  u32 (const std::string& four)
  {
    std::uint32_t value = 0;
    std::memcpy (&value, four.data (), 4);  // little-endian, as the format and ROS hosts are
    return value;
  }

  /** The fields of a record header: each a 4-byte length, then name=value. */
  std::map<std::string, std::string>
  fields (const std::string& header, std::uint64_t record_at, const std::string& what) const
  {
    std::map<std::string, std::string> fields;
    for (std::size_t i = 0; i < header.size ();) {
      const std::size_t length = i + 4 <= header.size () ? u32 (header.substr (i, 4)) : header.size ();
      const std::size_t begin = i + 4, equals = header.find ('=', std::min (begin, header.size ()));
      if (length > header.size () - std::min (begin, header.size ()) || equals >= begin + length)
        fail (record_at, "the " + what + " record's header holds a field whose length runs past it, or without '='");
      fields[header.substr (begin, equals - begin)] = header.substr (equals + 1, begin + length - equals - 1);
      i = begin + length;
    }
    return fields;
  }

  /** The record at \a at of \a bytes, which must be of kind \a op. */
  Record
  record (const Bytes& bytes, std::uint64_t at, std::uint8_t op, const std::string& what)
  {
    Record r;
    r.at = bytes.base + at;
    const std::uint32_t header_size = u32 (read (bytes, at, 4, at));
    r.fields = fields (read (bytes, at + 4, header_size, at), r.at, what);
    r.data_size = u32 (read (bytes, at + 4 + header_size, 4, at));
    r.data_at = at + 8 + header_size;
    if (r.data_size > bytes.size - r.data_at)
      fail (r.at, "the " + what + " record's data (" + std::to_string (r.data_size) + " bytes) runs past the end of the " +
                      (bytes.chunk ? "chunk" : "file"));
    const auto found = r.fields.find ("op");
    if (found == r.fields.end () || found->second.size () != 1 || found->second[0] != static_cast<char> (op))
      fail (r.at, "expected a " + what + " record, found " +
                      (found == r.fields.end () ? "a record without op" : "another kind of record"));
    r.data_at += bytes.base;
    return r;
  }

  /** The field \a name of \a r, a little-endian integer of sizeof (T) bytes. */
  template <typename T>
  T
  number (const Record& r, const std::string& name) const
  {
    const auto found = r.fields.find (name);
    if (found == r.fields.end () || found->second.size () != sizeof (T))
      fail (r.at, "the record's " + name + " field is missing or not " + std::to_string (sizeof (T)) + " bytes long");
    T value = 0;
    std::memcpy (&value, found->second.data (), sizeof (T));
    return value;
  }

  /** The chunk at \a at, its \a connections index records and the messages they index. */
  void
  checkChunk (std::uint64_t at, std::uint32_t connections)
  {
    const Record chunk = record (bag_, at, kChunk, "chunk");
    const std::uint32_t size = number<std::uint32_t> (chunk, "size");
    const auto compression = chunk.fields.find ("compression");
    if (compression == chunk.fields.end ())
      fail (at, "the chunk record has no compression field");
    const bool plain = compression->second == "none";
    if (plain && chunk.data_size != size)
      fail (at, "an uncompressed chunk of " + std::to_string (size) + " bytes holds " +
                    std::to_string (chunk.data_size));
    const Bytes messages{chunk.data_at, size, true};
    std::uint64_t next = chunk.end ();
    for (std::uint32_t k = 0; k < connections; ++k)
      next = checkIndex (next, messages, plain);
  }

  /** The index record at \a at. For a connection of the topics read, each entry's offset
   *  must lie in its chunk (\a messages) and, when the chunk is uncompressed (\a plain),
   *  at a message data record of the connection. Returns where the next record starts. */
  std::uint64_t
  checkIndex (std::uint64_t at, const Bytes& messages, bool plain)
  {
    const Record index = record (bag_, at, kIndexData, "index data");
    const std::uint32_t connection = number<std::uint32_t> (index, "conn");
    const std::uint32_t count = number<std::uint32_t> (index, "count");
    if (index.data_size != 12ull * count)
      fail (at, "an index of " + std::to_string (count) + " messages holds " + std::to_string (index.data_size) +
                    " bytes, not 12 per message");
    if (!read_connections_.count (connection))
      return index.end ();  // librosbag follows none of its entries
    const std::string entries = read (bag_, index.data_at, index.data_size);
    for (std::uint32_t e = 0; e < count; ++e) {
      const std::uint32_t offset = u32 (entries.substr (12 * e + 8, 4));
      if (offset >= messages.size)
        fail (index.data_at + 12 * e, "an index entry's offset " + std::to_string (offset) +
                                          " lies beyond its chunk's " + std::to_string (messages.size) + " bytes");
      if (plain && number<std::uint32_t> (record (messages, offset, kMessageData, "message data"), "conn") !=
                       connection)
        fail (messages.base + offset, "the message indexed for connection " + std::to_string (connection) +
                                          " belongs to another");
    }
    return index.end ();
  }

  std::string path_;
  std::set<std::string> topics_;
  std::set<std::uint32_t> read_connections_;  // the connections of topics_
  std::ifstream file_;
  Bytes bag_;
  std::string chunk_;  // the data of the chunk at chunk_at_, once a message of it is read
  std::uint64_t chunk_at_ = 0;
};

}  // namespace

void
checkRosbagStructure (const std::string& path, const std::vector<std::string>& topics)
{
  const std::string problem = unreadableFileProblem (path);
  if (!problem.empty ())
    throw LogError (path + ": cannot read the ROS bag: " + problem);
  BagChecker (path, topics).check ();
}

}  // namespace pcl_crf
