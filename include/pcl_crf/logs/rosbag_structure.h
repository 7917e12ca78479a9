#pragma once

#include <pcl_crf/logs/laser_log.h>

#include <string>
#include <vector>

namespace pcl_crf {

/** \brief Checks the records of a ROS1 bag v2.0 that a reader follows, before librosbag
 *  reads them: librosbag trusts their lengths and offsets, and one flipped byte in a
 *  chunk's or an index record's header, or in an index entry, made it read out of
 *  bounds and crash (SIGSEGV) instead of throwing.
 *
 *  Checked, following the index as librosbag does: the bag header record (index_pos
 *  within the file, conn_count and chunk_count records that fit after it); the
 *  connection and chunk-info records at index_pos; the chunk record each chunk info
 *  points to and the index records after it (one per connection of the chunk, 12 bytes
 *  per entry); and, for the connections of \a topics, each indexed message: in an
 *  uncompressed chunk a message data record of the connection must lie at its offset,
 *  in a compressed one the offset must lie within the chunk's uncompressed size. Every
 *  record's header length, header fields (length, then name=value) and data length must
 *  stay within the file (or its chunk). The messages of other topics are not read, so a
 *  damaged one of them is no error. Files that do not start with "#ROSBAG V2.0" are left
 *  to librosbag.
 *
 *  It reads the record headers, the indexes and the headers of the indexed messages of
 *  \a topics (not the messages' data), and needs no ROS library. readRosbagLog (with its
 *  scan and pose topics) and listRosbagTopics (with none) call it first.
 *  \param[in] path the bag file
 *  \param[in] topics the topics whose messages will be read (default none)
 *  \throws LogError naming the file, the byte offset of the record and the problem.
 *
 *  \code
 *  pcl_crf::checkRosbagStructure ("overtakes.bag", {"/scan", "/ego_pose"});
 *  \endcode
 */
void
checkRosbagStructure (const std::string& path, const std::vector<std::string>& topics = {});

}  // namespace pcl_crf
