// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Where the bundled datasets are: installed beside the executable's prefix
// (<prefix>/share/sonargrid/datasets), or the source tree's datasets/ when run from a build tree.

#include <QString>

namespace sg::app {

// The folder, or an empty string when neither exists.
QString bundledDatasetsDirectory();

}  // namespace sg::app
