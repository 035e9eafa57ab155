"""Live widgets and plots of the lessons, thin over the session's client node.

Lesson 7 plots /odom speed with every parameter change marked (`SpeedPlot`); lesson 11 shows
/parameter_events as a table (`EventsTable`) and a panel of sliders built from a node's
descriptors (`ParameterPanel`), which follows its node's life (`NodeNotRunningError` while the
node is gone).
"""

from .events import EventsTable, ParameterChange
from .node_life import NodeNotRunningError
from .param_panel import ParameterPanel
from .speed_plot import SpeedPlot

__all__ = ["EventsTable", "NodeNotRunningError", "ParameterChange", "ParameterPanel", "SpeedPlot"]
