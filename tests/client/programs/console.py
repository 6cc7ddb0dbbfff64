# Console logging as rcutils prints it: severities, levels, filters, the format variable and colours.
import rclpy.logging

log = rclpy.logging.get_logger("console_demo")
log.debug("not shown at INFO")
log.info("info line")
log.warning("warning line")
log.error("error line")
log.fatal("fatal line")
log.set_level(rclpy.logging.LoggingSeverity.DEBUG)
log.debug("debug line")
for i in range(3):
    log.info(f"once {i}", once=True)
    log.info(f"skip first {i}", skip_first=True)
child = log.get_child("child")
child.info("child line")
rclpy.logging.set_logger_level("console_demo.child", rclpy.logging.LoggingSeverity.ERROR)
child.warning("hidden child warning")
print("levels", int(log.get_effective_level()), int(child.get_effective_level()), flush=True)
