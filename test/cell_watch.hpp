// What the cell rostests watch: the phase, the events, the grasp object and each finger's state, kept under one
// lock (the spinner's threads write, the test reads a snapshot).
#pragma once

#include <ros/ros.h>
#include <std_msgs/String.h>

#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/GraspObject.h"

namespace pf_test {

class CellWatch {
 public:
  struct Snapshot {
    std::string phase, event;  // the latest of each
    std::vector<std::string> events;  // every event since the watch started
    pneumatic_finger::GraspObject::ConstPtr object;
    std::map<std::string, pneumatic_finger::FingerModelState::ConstPtr> states;  // by finger namespace
  };

  explicit CellWatch(ros::NodeHandle& nh) {
    subs_.push_back(nh.subscribe<std_msgs::String>("/cell/phase", 10, [this](const std_msgs::String::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      now_.phase = m->data;
    }));
    subs_.push_back(nh.subscribe<std_msgs::String>("/cell/events", 10, [this](const std_msgs::String::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      now_.event = m->data;
      now_.events.push_back(m->data);
    }));
    subs_.push_back(nh.subscribe<pneumatic_finger::GraspObject>(
        "/grasp_object", 10, [this](const pneumatic_finger::GraspObject::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          now_.object = m;
        }));
    for (const std::string f : {"finger_a", "finger_b", "finger_c"}) {
      subs_.push_back(nh.subscribe<pneumatic_finger::FingerModelState>(
          "/" + f + "/finger_state", 10, [this, f](const pneumatic_finger::FingerModelState::ConstPtr& m) {
            std::lock_guard<std::mutex> lock(mutex_);
            now_.states[f] = m;
          }));
    }
  }

  Snapshot snapshot() {
    std::lock_guard<std::mutex> lock(mutex_);
    return now_;
  }

 private:
  std::mutex mutex_;
  Snapshot now_;
  std::vector<ros::Subscriber> subs_;
};

}  // namespace pf_test
