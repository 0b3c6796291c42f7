#include "kinematics/compact_motion.h"

#include <cassert>

namespace mocapsolve {

CompactMotion::CompactMotion(const Motion& motion)
    : frame_rate_(motion.frame_rate), num_frames_(motion.num_frames()) {
  if (motion.frames.empty()) return;
  const Pose& first = motion.frames.front();
  num_joints_ = static_cast<int>(first.rotations.size());
  assert(first.translations.size() == first.rotations.size());
  moving_column_.assign(num_joints_, -1);
  fixed_translations_ = first.translations;
  int moving = 0;
  for (int j = 0; j < num_joints_; ++j) {
    for (const Pose& pose : motion.frames) {
      assert(static_cast<int>(pose.translations.size()) == num_joints_);
      assert(static_cast<int>(pose.rotations.size()) == num_joints_);
      if (pose.translations[j] != first.translations[j]) {
        moving_column_[j] = moving++;
        break;
      }
    }
  }
  rotations_.resize(static_cast<size_t>(num_frames_) * num_joints_ * 4);
  translations_.resize(static_cast<size_t>(num_frames_) * moving * 3);
  float* r = rotations_.data();
  float* t = translations_.data();
  for (const Pose& pose : motion.frames) {
    for (int j = 0; j < num_joints_; ++j) {
      const Eigen::Quaterniond& q = pose.rotations[j];
      *r++ = static_cast<float>(q.w());
      *r++ = static_cast<float>(q.x());
      *r++ = static_cast<float>(q.y());
      *r++ = static_cast<float>(q.z());
      if (moving_column_[j] < 0) continue;
      for (int k = 0; k < 3; ++k) *t++ = static_cast<float>(pose.translations[j][k]);
    }
  }
}

Eigen::Quaterniond CompactMotion::Rotation(int f, int joint) const {
  const float* r = rotations_.data() + (static_cast<size_t>(f) * num_joints_ + joint) * 4;
  return Eigen::Quaterniond(r[0], r[1], r[2], r[3]).normalized();
}

Eigen::Vector3d CompactMotion::Translation(int f, int joint) const {
  const int column = moving_column_[joint];
  if (column < 0) return fixed_translations_[joint];
  const size_t moving = translations_.size() / (static_cast<size_t>(num_frames_) * 3);
  const float* t = translations_.data() + (static_cast<size_t>(f) * moving + column) * 3;
  return Eigen::Vector3d(t[0], t[1], t[2]);
}

void CompactMotion::Frame(int f, Pose* pose) const {
  pose->rotations.resize(num_joints_);
  pose->translations.resize(num_joints_);
  for (int j = 0; j < num_joints_; ++j) {
    pose->rotations[j] = Rotation(f, j);
    pose->translations[j] = Translation(f, j);
  }
}

Pose CompactMotion::Frame(int f) const {
  Pose pose;
  Frame(f, &pose);
  return pose;
}

Motion CompactMotion::ToMotion() const {
  Motion motion;
  motion.frame_rate = frame_rate_;
  motion.frames.resize(num_frames_);
  for (int f = 0; f < num_frames_; ++f) Frame(f, &motion.frames[f]);
  return motion;
}

int CompactMotion::num_moving() const {
  int moving = 0;
  for (int column : moving_column_) moving += column >= 0 ? 1 : 0;
  return moving;
}

void CompactMotion::Reserve(int frames) {
  reserved_frames_ = frames;
  if (num_joints_ > 0) rotations_.reserve(static_cast<size_t>(frames) * num_joints_ * 4);
}

void CompactMotion::Append(const Motion& motion, int first, int count) {
  if (count <= 0) return;
  if (num_frames_ == 0) {
    const int reserved = reserved_frames_;
    Motion part;
    part.frame_rate = motion.frame_rate;
    part.frames.assign(motion.frames.begin() + first, motion.frames.begin() + first + count);
    *this = CompactMotion(part);
    if (reserved > 0) {
      rotations_.reserve(static_cast<size_t>(reserved) * num_joints_ * 4);
      translations_.reserve(static_cast<size_t>(reserved) * num_moving() * 3);
      reserved_frames_ = reserved;
    }
    return;
  }
  // Joints fixed so far that move in the new frames: a column each, the earlier frames at
  // their fixed value.
  const int old_moving = num_moving();
  int moving = old_moving;
  std::vector<int> columns = moving_column_;
  for (int j = 0; j < num_joints_; ++j) {
    if (columns[j] >= 0) continue;
    for (int f = first; f < first + count; ++f) {
      if (motion.frames[f].translations[j] != fixed_translations_[j]) {
        columns[j] = moving++;
        break;
      }
    }
  }
  if (moving != old_moving) {
    std::vector<float> wider(static_cast<size_t>(num_frames_) * moving * 3);
    for (int f = 0; f < num_frames_; ++f) {
      for (int j = 0; j < num_joints_; ++j) {
        if (columns[j] < 0) continue;
        const Eigen::Vector3d t = Translation(f, j);
        for (int k = 0; k < 3; ++k) wider[(static_cast<size_t>(f) * moving + columns[j]) * 3 + k] = static_cast<float>(t[k]);
      }
    }
    if (reserved_frames_ > 0) wider.reserve(static_cast<size_t>(reserved_frames_) * moving * 3);
    translations_ = std::move(wider);
    moving_column_ = columns;
  }
  for (int f = first; f < first + count; ++f) {
    const Pose& pose = motion.frames[f];
    for (int j = 0; j < num_joints_; ++j) {
      const Eigen::Quaterniond& q = pose.rotations[j];
      rotations_.insert(rotations_.end(), {static_cast<float>(q.w()), static_cast<float>(q.x()),
                                           static_cast<float>(q.y()), static_cast<float>(q.z())});
    }
    const size_t row = translations_.size();
    translations_.resize(row + static_cast<size_t>(moving) * 3);
    for (int j = 0; j < num_joints_; ++j) {
      if (moving_column_[j] < 0) continue;
      for (int k = 0; k < 3; ++k) translations_[row + moving_column_[j] * 3 + k] = static_cast<float>(pose.translations[j][k]);
    }
  }
  num_frames_ += count;
}

size_t CompactMotion::bytes() const {
  return rotations_.capacity() * sizeof(float) + translations_.capacity() * sizeof(float) +
         fixed_translations_.capacity() * sizeof(Eigen::Vector3d) + moving_column_.capacity() * sizeof(int);
}

}  // namespace mocapsolve
