"""pneumatic_finger: the model of a soft pneumatic finger (pneumatic_finger.core) and the package's ROS messages
(pneumatic_finger.msg, pneumatic_finger.srv)."""
