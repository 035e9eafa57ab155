"""The page of the 3D view: meshcat's viewer, drawn on demand, with the course's toolbar.

`server.LocalBridge` serves it at `/static/`; its websocket connects relative to where the
page was served from ("/" directly, "/proxy/<port>/" behind Jupyter). A page nobody can see
tells the server `hidden` (and `shown` again), so it gets no poses meanwhile.
"""

from __future__ import annotations

import tornado.web

from .page_access import PANEL_JS, ROBOT_STATE_JS, TOOLBAR_JS

__all__ = ["PAGE", "ViewerPage"]

# The toolbar (TF frames, Controls) is one Tab stop; the line under it says where the robot is
# (page_access). White on at least 70 % black: AA contrast over any part of the scene.
PAGE = (
    """<!DOCTYPE html>
<html lang="en"><head><meta charset=utf-8><title>3D view of the simulated robot</title>
<style>body {margin: 0} #meshcat-pane {width: 100vw; height: 100vh; overflow: hidden}
#view-tools {position: absolute; left: 8px; top: 8px; display: flex; gap: 6px;
  align-items: center}
#view-tools > *, #robot-state {padding: 2px 6px; border: 0; border-radius: 4px;
  font: 13px sans-serif; color: #fff; background: rgba(0, 0, 0, 0.7); user-select: none}
#robot-state {position: absolute; left: 8px; bottom: 8px; margin: 0}</style>
</head><body><div id="meshcat-pane"></div>
<div id="view-tools" role="toolbar" aria-label="3D view">
<label id="tf-toggle" title="the frames /tf and /tf_static describe (x red, y green, z blue)">
<input type="checkbox" id="tf-frames"> TF frames</label>
<button type="button" id="view-controls" aria-expanded="false">Controls</button></div>
<p id="robot-state" role="status" aria-live="polite" aria-atomic="true">Robot: waiting for
the simulation</p>
<script src="main.min.js"></script>
<script>
// Drawn on demand: meshcat's own loop (off here) asks the browser for a frame 60 times a
// second for as long as the page is open, with nothing new to draw, which costs a browser
// without a GPU real work for a still robot. Here a frame is asked for
// when meshcat marks the scene changed (a pose, the camera moved, a resize), and each
// frame of a playing animation asks for the next.
var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"), false);
(function () {
  var asked = false;
  function frame() {
    asked = false;
    viewer.animator.update();  // a playing animation marks the scene changed: next frame
    if (viewer.needs_render) { viewer.render(); }
  }
  function ask() {
    if (!asked) { asked = true; requestAnimationFrame(frame); }
  }
  var mark = viewer.set_dirty.bind(viewer);
  viewer.set_dirty = function () { mark(); ask(); };
  viewer.animate = ask;  // what meshcat calls to restart its loop after a recording
  var animator = Object.getPrototypeOf(viewer.animator), play = animator.play;
  animator.play = function () { play.call(this); ask(); };
  ask();
})();
// One message carries a frame's poses: paths and their 4x4 matrices (column-major), in a row.
var handle_one = viewer.handle_command.bind(viewer);
viewer.handle_command = function (command) {
  if (command.type !== "set_transforms") { return handle_one(command); }
  for (var i = 0; i < command.paths.length; i++) {
    handle_one({type: "set_transform", path: command.paths[i],
                matrix: command.matrices.subarray(16 * i, 16 * i + 16)});
  }
};
// The simulation draws its TF frames under /meshcat/tf, hidden; this box shows them.
// Drawn on top of the robot's shapes (no depth test): most frames sit inside the chassis.
document.getElementById("tf-frames").addEventListener("change", function (event) {
  var frames = viewer.scene_tree.find(["meshcat", "tf"]);
  frames.object.traverse(function (part) {
    if (part.material) { part.material.depthTest = false; part.renderOrder = 1; }
  });
  viewer.set_property(["meshcat", "tf"], "visible", event.target.checked);
});
// The websocket lives at the page's own prefix: "/" directly, "/proxy/<port>/" behind Jupyter.
var base = location.href.split(/[?#]/)[0].replace(/static\\/(index\\.html)?$/, "");
viewer.connect(base.replace(/^http/, "ws"));
// A view nobody can see (its notebook's tab in the background, scrolled out of sight, the
// browser tab hidden) tells the server so, which then sends it no poses until it is seen
// again: frames drawn for a hidden view pile up and freeze the page when its notebook's tab
// comes back. Chromium runs animation frames even in an iframe under
// `display: none`: what says "seen" is the pane's intersection with the top page's viewport.
var shown = true, visible = {pane: true, tab: true};
function tell(now) {
  shown = now;
  var socket = viewer.connection;
  if (socket && socket.readyState === 1) { socket.send(now ? "shown" : "hidden"); }
}
function update() {
  var now = visible.pane && visible.tab;
  if (now !== shown) { tell(now); }
}
new IntersectionObserver(function (entries) {
  visible.pane = entries[entries.length - 1].isIntersecting;
  update();
}).observe(document.getElementById("meshcat-pane"));
document.addEventListener("visibilitychange", function () {
  visible.tab = document.visibilityState === "visible";
  update();
});
if (viewer.connection) {
  viewer.connection.addEventListener("open", function () { if (!shown) { tell(false); } });
}
</script>
<script>
"""
    + PANEL_JS
    + 'accessiblePanel(viewer, document.getElementById("view-controls"));\n'
    + TOOLBAR_JS
    + ROBOT_STATE_JS
    + "</script></body></html>\n"
)


class ViewerPage(tornado.web.RequestHandler):
    """meshcat's page, but connecting its websocket relative to where it was served from."""

    def get(self, _name: str = "") -> None:
        self.set_header("Cache-Control", "no-store")
        self.write(PAGE)
