"""rclpy.lifecycle for diffctl: managed nodes on rcl_lifecycle's default state machine (`state_machine`,
pure), the node mixin with its services and transition events (`node`), managed entities and the
publisher that only publishes while active (`managed_entity`)."""
