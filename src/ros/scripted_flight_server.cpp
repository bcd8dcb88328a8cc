#include "surface_nbv/ros/scripted_flight_server.h"

#include <cmath>

#include <rosgraph_msgs/Clock.h>
#include <tf2_eigen/tf2_eigen.h>

namespace surface_nbv {

Status ScriptedFlightNodeConfig::validate() const {
  if (Status s = flight.validate(); !s) return s;
  if (world_frame.empty() || body_frame.empty() || world_frame == body_frame) {
    return Status::Error("world_frame and body_frame expected two different frame names");
  }
  if (!std::isfinite(tf_rate) || tf_rate <= 0.0 || tf_rate > 1000.0) return Status::Error("tf_rate expected in (0, 1000]");
  if (!std::isfinite(stop_after) || stop_after < 0.0) return Status::Error("stop_after expected >= 0 s");
  if (!std::isfinite(time_scale) || time_scale <= 0.0 || time_scale > 100.0) {
    return Status::Error("time_scale expected in (0, 100]");
  }
  return Status::Ok();
}

Status loadScriptedFlightParams(const ros::NodeHandle& priv, ScriptedFlightNodeConfig* c) {
  ParamReader reader(priv);
  reader.get("target_min", &c->flight.target.min);
  reader.get("target_max", &c->flight.target.max);
  reader.get("standoff", &c->flight.standoff);
  reader.get("altitudes", &c->flight.altitudes);
  reader.get("speed", &c->flight.speed);
  reader.get("world_frame", &c->world_frame);
  reader.get("body_frame", &c->body_frame);
  reader.get("tf_rate", &c->tf_rate);
  reader.get("publish_clock", &c->publish_clock);
  reader.get("time_scale", &c->time_scale);
  reader.get("loop", &c->loop);
  reader.get("stop_after", &c->stop_after);
  reader.checkUnknown();
  if (Status s = reader.status(); !s) return s;
  if (Status s = c->validate(); !s) return Status::Error(priv.getNamespace() + "/" + s.message());
  return Status::Ok();
}

ScriptedFlightServer::ScriptedFlightServer(ros::NodeHandle nh, const ScriptedFlightNodeConfig& config)
    : config_(config), flight_(config.flight) {
  if (config_.publish_clock) clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  wall_start_ = ros::WallTime::now();
  start_ = config_.publish_clock ? ros::Time(1.0) : ros::Time::now();
  ROS_INFO("scripted_flight: %.1f m path, %.1f s at %.2f m/s, %zu loop(s)", flight_.length(), flight_.duration(),
           config_.flight.speed, config_.flight.altitudes.size());
  timer_ = nh.createWallTimer(ros::WallDuration(1.0 / config_.tf_rate), &ScriptedFlightServer::onTimer, this);
}

void ScriptedFlightServer::onTimer(const ros::WallTimerEvent&) {
  ros::Time now;
  if (config_.publish_clock) {
    sim_elapsed_ += config_.time_scale / config_.tf_rate;
    now = start_ + ros::Duration(sim_elapsed_);
    rosgraph_msgs::Clock clock;
    clock.clock = now;
    clock_pub_.publish(clock);
  } else {
    now = ros::Time::now();
    if (start_.isZero()) start_ = now;  // waiting for an external /clock
    if (now.isZero()) return;
  }
  double t = (now - start_).toSec();
  if (config_.loop) t = std::fmod(t, flight_.duration());
  const double end = config_.stop_after > 0.0 ? std::min(config_.stop_after, flight_.duration()) : flight_.duration();
  t = std::min(t, end);
  if (t >= end && !finished_logged_) {
    finished_logged_ = true;
    ROS_INFO("scripted_flight: flight finished after %.1f s, hovering at the end", end);
  }
  geometry_msgs::TransformStamped tf = tf2::eigenToTransform(flight_.poseAt(t));
  tf.header.stamp = now;
  tf.header.frame_id = config_.world_frame;
  tf.child_frame_id = config_.body_frame;
  broadcaster_.sendTransform(tf);
}

}  // namespace surface_nbv
