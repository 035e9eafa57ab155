import rclpy
from geometry_msgs.msg import TwistStamped
rclpy.init()
node = rclpy.create_node('stamped_talker')
pub = node.create_publisher(TwistStamped, '/stamped', 10)
def tick():
    msg = TwistStamped()
    msg.header.stamp = node.get_clock().now().to_msg()
    pub.publish(msg)
node.create_timer(0.1, tick)
try:
    rclpy.spin(node)
except KeyboardInterrupt:  # stopped with Ctrl-C
    pass
