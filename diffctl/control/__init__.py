"""ros2_control in Python: controller manager, hardware plugins, controllers, spawner and CLI.

Every node here is a diffctl.client Node (rclpy's API): the manager (`/controller_manager`, or the
gz_ros2_control plugin's `<controller_manager_name>` in its `<ros><namespace>`, manager_node.py) and one node per
controller (`/<ns>/<controller>`, controller_node.py), with their parameters declared as controller_manager
and the controllers' generate_parameter_library YAMLs declare them, so `param list/describe/set` match.

Writing a controller (controller_interface.py has the full contract; diff_drive, joint_state_broadcaster and
forward_command in controllers/ are worked examples):

    class MyController(ControllerInterface):              # or ChainableControllerInterface
        def on_init(self):                                 # declare parameters: param_decl.declare_all(
            ...                                            #   self.get_node(), DECLS, self.get_name())
        def command_interface_configuration(self):         # InterfaceConfiguration.individual([...]) /
            return InterfaceConfiguration.individual(...)  #   .all() / .none()
        def state_interface_configuration(self): ...
        def on_configure(self, previous_state): ...        # publishers/subscriptions on self.get_node();
        def on_activate(self, previous_state): ...         #   wrap publishers in RealtimePublisher
        def on_deactivate(self, previous_state): ...       # hooks: CallbackReturn.SUCCESS/None, or
        def on_cleanup / on_shutdown / on_error(self, previous_state): ...   # FAILURE/ERROR/raise
        def update(self, time, period) -> ReturnType:      # client Time / Duration; ReturnType.OK/ERROR
            ...                                            # self.command_interfaces[i].value = v

    Chainable: set self.exported_reference_interface_names (and exported_state_interface_names), implement
    update_reference_from_subscribers(time, period) and update_and_write_commands(time, period), optionally
    on_set_chained_mode(chained) -> bool; read references from self.reference_interfaces[i].value.

Register it under the entry-point group `diffctl.controllers` as "<pkg>/<Class>" (plugin_registry.py). Base
helpers: get_node(), get_name(), get_update_rate(), get_robot_description(), get_lifecycle_state(),
auto_declare(name, default).
"""
