// The COMMAND_LONG helpers; the messages' layouts and pack/unpack live in the header.
#include "drivers/mavlink/mavlink_messages.hpp"

namespace rovctl::drivers::mavlink {

CommandLong arm_disarm(std::uint8_t target_system, std::uint8_t target_component, bool arm,
                       bool force) {
  CommandLong c;
  c.command = kCmdComponentArmDisarm;
  c.target_system = target_system;
  c.target_component = target_component;
  c.params[0] = arm ? 1.0F : 0.0F;
  c.params[1] = force ? kArmDisarmForceMagic : 0.0F;
  return c;
}

CommandLong do_set_mode(std::uint8_t target_system, std::uint8_t target_component,
                        std::uint32_t custom_mode) {
  CommandLong c;
  c.command = kCmdDoSetMode;
  c.target_system = target_system;
  c.target_component = target_component;
  c.params[0] = kModeFlagCustomModeEnabled;
  c.params[1] = static_cast<float>(custom_mode);
  return c;
}

CommandLong run_prearm_checks(std::uint8_t target_system, std::uint8_t target_component) {
  CommandLong c;
  c.command = kCmdRunPrearmChecks;
  c.target_system = target_system;
  c.target_component = target_component;
  return c;
}

CommandLong set_message_interval(std::uint8_t target_system, std::uint8_t target_component,
                                 std::uint32_t message_id, float interval_us) {
  CommandLong c;
  c.command = kCmdSetMessageInterval;
  c.target_system = target_system;
  c.target_component = target_component;
  c.params[0] = static_cast<float>(message_id);
  c.params[1] = interval_us;
  return c;
}

}  // namespace rovctl::drivers::mavlink
