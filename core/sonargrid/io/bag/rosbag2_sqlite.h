// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// rosbag2's SQLite storage (docs/formats.md, "ROS bags"): a .db3 file with the tables
// topics(id, name, type, serialization_format, offered_qos_profiles) and messages(id, topic_id,
// timestamp, data), read with Debian's libsqlite3, read-only. Messages come in timestamp order.

#include <memory>
#include <string>
#include <string_view>

#include "sonargrid/io/bag/bag.h"

namespace sg::bag {

// Opens the .db3 at `path` read-only and reads its topics. Throws BagError when it is not an
// SQLite database or lacks rosbag2's tables.
std::unique_ptr<Reader> openSqlite(const std::string& path);
// The same for a database in memory (fuzz targets, tests); `name` is used in messages.
std::unique_ptr<Reader> openSqliteBytes(std::string_view bytes, const std::string& name);

}  // namespace sg::bag
