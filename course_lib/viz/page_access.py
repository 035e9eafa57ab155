"""What the course adds to meshcat's pages for keyboard and screen-reader users (pure).

Scripts, as text, that the live view's page (`server`) and the replay pages (`replay`) run
after `var viewer = new MeshCat.Viewer(...)`:
- `PANEL_JS` defines `accessiblePanel(viewer, toggle)`: meshcat's control panel (a dat.GUI
  tree of about a hundred checkboxes and text boxes) gets a name on every control, folder
  titles and actions that a keyboard opens and runs (Enter, Space), a visible focus, and Escape
  to close it; whatever a closed folder (or the closed panel) hides is inert, out of the Tab
  order and of the screen reader's page, so a closed panel is one stop, not a hundred.
  `toggle` is the page's own button that opens the panel (dat.GUI's own bar is then hidden);
  without it, dat.GUI's "Open Controls" bar is the button.
- `TOOLBAR_JS`: the live view's toolbar (TF frames, Controls) is one Tab stop; the arrow keys,
  Home and End move between its controls (WAI-ARIA's toolbar pattern).
- `ROBOT_STATE_JS`: the line at the foot of the live view that says, in words, where the robot
  is and how fast it goes ("Robot at x 1.20 m, y 0.00 m, heading 0°, speed 0.20 m/s"): a
  polite live region, rewritten at most every `SAY_EVERY_MS` and only when a number changed
  noticeably (5 cm, 5°, 0.02 m/s), so a screen reader reads it at a pace a person follows.
  The speed is the forward distance the page saw the robot cover in the last second; a view
  nobody sees gets no poses (`server`) and says nothing new until it is seen again.
"""

from __future__ import annotations

__all__ = ["PANEL_JS", "ROBOT_STATE_JS", "SAY_EVERY_MS", "TOOLBAR_JS"]

SAY_EVERY_MS = 2500

PANEL_JS = r"""function accessiblePanel(viewer, toggle) {
  var style = document.createElement("style");
  style.textContent = ".dg [tabindex]:focus-visible, .dg input:focus-visible, " +
    ".dg select:focus-visible, #view-tools :focus-visible " +
    "{outline: 2px solid #ffbf47; outline-offset: 1px; box-shadow: 0 0 0 4px #000}" +
    (toggle ? " .dg.main > .close-button {display: none}" : "");
  document.head.appendChild(style);
  if (toggle) {
    toggle.addEventListener("click", function () {
      viewer.gui.closed = !viewer.gui.closed;
      toggle.setAttribute("aria-expanded", String(!viewer.gui.closed));
    });
  }
  var build = viewer.create_scene_tree.bind(viewer);
  viewer.create_scene_tree = function () {  // a scene loaded from a file: a new panel
    build();
    access(viewer.gui);
  };
  access(viewer.gui);
  function access(gui) {
    var bar = gui.domElement.querySelector(":scope > .close-button");
    function operable(element, name) {  // a div or span that a click operates: a button
      if (name && element.getAttribute("aria-label") !== name) {
        element.setAttribute("aria-label", name);
      }
      if (element.getAttribute("role") === "button") return;
      element.setAttribute("role", "button");
      element.tabIndex = 0;
      element.addEventListener("keydown", function (event) {
        if (event.key !== "Enter" && event.key !== " ") return;
        event.preventDefault();
        element.click();
        sync();  // says the new state at once (the observer's sync comes a moment later)
      });
    }
    function folders(element) {  // the titles of the folders holding it, outermost first
      var names = [];
      for (var li = element.closest("li.folder"); li; li = li.parentElement.closest("li.folder")) {
        var title = li.querySelector(":scope > .dg > ul > li.title");
        if (title) names.unshift(title.textContent.trim());
      }
      return names.join(" / ");
    }
    function name(control) {
      var row = control.closest("li.cr"), label = row && row.querySelector(".property-name");
      var what = label ? label.textContent.trim() : "visible", where = folders(control);
      return where ? what + " (" + where + ")" : what;
    }
    function title(item, open) {  // a folder's title row: its text in a button
      var button = item.firstElementChild;
      if (!button || !button.classList.contains("course-folder")) {
        button = document.createElement("span");
        button.className = "course-folder";
        while (item.firstChild) button.appendChild(item.firstChild);
        item.appendChild(button);
        operable(button);  // its click reaches the row, which opens and closes the folder
      }
      button.setAttribute("aria-expanded", String(open));
    }
    function sync() {
      gui.domElement.querySelectorAll("ul").forEach(function (list) {
        var closed = list.classList.contains("closed");
        for (var item of list.children) {
          if (item.classList.contains("title")) title(item, !closed);
          else if (item.inert !== closed) {
            item.inert = closed;  // out of the Tab order and of the accessibility tree
            // said twice: not every tool knows inert
            if (closed) item.setAttribute("aria-hidden", "true");
            else item.removeAttribute("aria-hidden");
          }
        }
      });
      gui.domElement.querySelectorAll("input, select").forEach(function (control) {
        var said = name(control);
        if (control.getAttribute("aria-label") !== said) control.setAttribute("aria-label", said);
      });
      gui.domElement.querySelectorAll("li.cr.function > div").forEach(function (row) {
        var label = row.querySelector(".property-name");
        operable(row, label ? label.textContent.trim() : "run");
      });
      var open = String(!gui.closed);
      if (bar && !toggle) operable(bar);
      [toggle || bar].forEach(function (button) {
        if (button && button.getAttribute("aria-expanded") !== open) {
          button.setAttribute("aria-expanded", open);
        }
      });
    }
    var pending = false;
    new MutationObserver(function () {  // folders come and go with the scene
      if (!pending) { pending = true; setTimeout(function () { pending = false; sync(); }); }
    }).observe(gui.domElement, {subtree: true, childList: true, attributeFilter: ["class"]});
    gui.domElement.addEventListener("keydown", function (event) {
      if (event.key !== "Escape" || gui.closed) return;
      gui.closed = true;
      (toggle || bar).focus();
    });
    sync();
  }
}
"""

TOOLBAR_JS = r"""(function () {
  var tools = document.getElementById("view-tools");
  var items = Array.from(tools.querySelectorAll("input, button"));
  function rove(to) { items.forEach(function (item) { item.tabIndex = item === to ? 0 : -1; }); }
  rove(items[0]);
  tools.addEventListener("focusin", function (event) {
    if (items.indexOf(event.target) >= 0) rove(event.target);
  });
  tools.addEventListener("keydown", function (event) {
    var at = items.indexOf(document.activeElement), last = items.length - 1;
    var to = {ArrowRight: at + 1, ArrowDown: at + 1, ArrowLeft: at - 1, ArrowUp: at - 1,
              Home: 0, End: last}[event.key];
    if (at < 0 || to === undefined) return;
    event.preventDefault();
    var next = items[(to + items.length) % items.length];
    rove(next);
    next.focus();
  });
})();
"""

ROBOT_STATE_JS = r"""(function () {
  var line = document.getElementById("robot-state");
  var SAY_EVERY_MS = @SAY_EVERY_MS@, SPEED_OVER_MS = 1000;
  var samples = [], said = null, saidAt = -Infinity;
  function base() {  // the robot's body in meshcat's scene; undefined until it is drawn
    var node = viewer.scene_tree;
    ["meshcat", "mujoco", "base_link"].forEach(function (name) {
      node = node && node.children[name];
    });
    return node && node.object;
  }
  function fixed(value) {  // two decimals, never "-0.00"
    var text = value.toFixed(2);
    return text === "-0.00" ? "0.00" : text;
  }
  function noticeable(now, before) {
    if (!before) return true;
    var turn = Math.abs(now.heading - before.heading) % 360;
    return Math.abs(now.x - before.x) >= 0.05 || Math.abs(now.y - before.y) >= 0.05 ||
      Math.min(turn, 360 - turn) >= 5 || Math.abs(now.speed - before.speed) >= 0.02;
  }
  function tick() {
    var body = base(), at = performance.now();
    if (!body || (typeof shown !== "undefined" && !shown)) { samples = []; return; }
    var q = body.quaternion;
    var yaw = Math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
    var pose = {at: at, x: body.position.x, y: body.position.y, yaw: yaw};
    samples.push(pose);
    while (samples.length > 1 && at - samples[1].at >= SPEED_OVER_MS) samples.shift();
    var from = samples[0], seconds = (at - from.at) / 1000;
    if (seconds * 1000 < SPEED_OVER_MS || at - saidAt < SAY_EVERY_MS) return;
    var forward = ((pose.x - from.x) * Math.cos(yaw) + (pose.y - from.y) * Math.sin(yaw));
    var heading = Math.round(yaw * 180 / Math.PI);
    var now = {x: pose.x, y: pose.y, heading: heading === -180 ? 180 : heading + 0,
               speed: forward / seconds};
    if (!noticeable(now, said)) return;
    said = now;
    saidAt = at;
    line.textContent = "Robot at x " + fixed(now.x) + " m, y " + fixed(now.y) +
      " m, heading " + now.heading + "°, speed " + fixed(now.speed) + " m/s";
  }
  setInterval(tick, 500);
})();
""".replace("@SAY_EVERY_MS@", str(SAY_EVERY_MS))
