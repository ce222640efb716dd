// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A log's start pose: where the robot stood, in the map's (the building's) frame, at the log's
// first scan. Odometry starts at 0 wherever the robot is switched on, so a map made from it lies
// in a frame of its own, and scoring it against a floor plan drawn from tape measurements gives
// nonsense. Placing the odometry at the start pose moves the whole path rigidly into the floor
// plan's frame (docs/formats.md, "Start pose").

#include <optional>
#include <string>
#include <string_view>

#include "sonargrid/data/dataset.h"

namespace sg {

// Moves every scan's odometry rigidly so that the first scan's becomes `start`: scan i is placed at
// start * inverse(odometry[0]) * odometry[i]. True poses are left as they are (they are already in
// the map's frame). A log without scans is left alone.
void placeOdometryAt(Dataset& log, const Pose2D& start);

// "X,Y,THETA": metres, metres and degrees (counter-clockwise from the map's x axis), the form
// --start-pose takes and formatStartPose writes. nullopt with `error` saying what is wrong.
std::optional<Pose2D> parseStartPose(std::string_view text, std::string* error = nullptr);
std::string formatStartPose(const Pose2D& pose);

}  // namespace sg
