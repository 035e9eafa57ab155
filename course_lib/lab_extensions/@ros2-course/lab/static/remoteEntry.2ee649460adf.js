// The ROS 2 course's JupyterLab plugin, written by hand (no build step): a module-federation
// container as JupyterLab loads prebuilt extensions (window._JUPYTERLAB[name] with init/get).
//
// Why: Run > Run All Cells on a notebook whose kernel was shut down runs every cell at once.
// The first cell starts a kernel; the others, seeing a kernel name pending, go straight on to
// execute, find no kernel yet and are skipped: only the first cell runs. Here, while a
// session's kernel is starting, the session says it has no kernel, so every other cell asks to
// start one too, and that start is single-flight: each cell waits for the one kernel, then all
// run, in order.
//
// Why the second plugin (issue 61): ipywidgets' sliders (noUiSlider) give their handle no
// name (the label beside it is not tied to it: axe's aria-input-field-name), and say their
// range and value to one decimal and their value unrounded (velocity's maximum 0.26 read 0.3,
// travel_time 2.5 read 2.4999999999999996). Here each handle is named by its label and says
// the true range and the value its readout shows; Escape leaves a widget for its cell (command
// mode: arrows and Shift+Enter work on cells again); a focused control shows an outline.
(function () {
  "use strict";
  var NAME = "@ros2-course/lab";

  function startOnce(context) {
    var proto = Object.getPrototypeOf(context);
    if (!proto || typeof proto.startKernel !== "function" || proto.__ros2CourseStartOnce) {
      return;
    }
    var start = proto.startKernel;
    var noKernel = Object.getOwnPropertyDescriptor(proto, "hasNoKernel");
    if (!noKernel || typeof noKernel.get !== "function") {
      return;
    }
    Object.defineProperty(proto, "hasNoKernel", {
      configurable: true,
      get: function () {
        var starting = Boolean(this.__ros2CourseStarting);
        var kernel = this.session && this.session.kernel;
        return noKernel.get.call(this) || (starting && !kernel);
      },
    });
    proto.startKernel = function () {
      var self = this;
      if (!self.__ros2CourseStarting) {
        self.__ros2CourseStarting = Promise.resolve(start.call(self)).finally(function () {
          self.__ros2CourseStarting = null;
        });
      }
      return self.__ros2CourseStarting;
    };
    proto.__ros2CourseStartOnce = true;
  }

  // A kernel killed while a cell runs is started again by the server; now and then the
  // page's connection to the new kernel stays "Unknown": nothing of the new kernel reached
  // it, and JupyterLab holds every request (the cells run) until the new kernel says it is
  // starting, which the idle kernel never says again. After STUCK_MS of that, the page
  // connects again and restarts that kernel (new, idle, nothing run in it yet: nothing is
  // lost), whose "starting" then reaches the page.
  var STUCK_MS = 10000;
  // ... and not again while the restart it asked for may still be under way (a busy host)
  var HEAL_AGAIN_MS = 60000;

  function wakeUp(kernel) {
    console.warn(NAME + ": the kernel connection stayed unknown; connecting and restarting");
    return kernel.reconnect().then(function () {
      return kernel.restart();
    });
  }

  function healStuck(context) {
    if (context.__ros2CourseHeals) {
      return;
    }
    context.__ros2CourseHeals = true;
    var timer = null;
    var healed = -Infinity;
    // Looked at again while the status stays "unknown": a first heal whose own restart got
    // stuck too (seen in `make chaos`: 300 s "Unknown") is followed by another, a minute on.
    function check() {
      timer = null;
      var kernel = context.session && context.session.kernel;
      if (context.isDisposed || !kernel || kernel.status !== "unknown") {
        return;
      }
      var wait = healed + HEAL_AGAIN_MS - Date.now();
      if (wait <= 0 && kernel.connectionStatus === "connected") {
        healed = Date.now();
        wait = HEAL_AGAIN_MS;
        wakeUp(kernel).catch(function () {});
      }
      timer = setTimeout(check, Math.max(wait, STUCK_MS));
    }
    context.statusChanged.connect(function (_sender, status) {
      if (timer !== null) {
        clearTimeout(timer);
        timer = null;
      }
      if (status === "unknown") {
        timer = setTimeout(check, STUCK_MS);
      }
    });
  }

  function watch(app) {
    var patch = function () {
      var widget = app.shell.currentWidget;
      if (widget && widget.sessionContext) {
        startOnce(widget.sessionContext);
        healStuck(widget.sessionContext);
      }
    };
    patch();
    if (app.shell.currentChanged) {
      app.shell.currentChanged.connect(patch);
    }
  }

  var plugin = {
    id: NAME + ":start-kernel-once",
    description:
      "Run All on a notebook without a kernel starts one kernel, then every cell; a kernel" +
      " connection stuck unknown after a restart connects again.",
    autoStart: true,
    activate: function (app) {
      watch(app);
    },
  };

  var SLIDER = ".jupyter-widgets.widget-slider";
  // noUiSlider rewrites these at each move; a disabled slider changes its own attribute
  var WATCHED = ["aria-valuemin", "aria-valuemax", "aria-valuenow", "aria-valuetext", "disabled"];
  var FOCUS_STYLE =
    ".jupyter-widgets .noUi-handle:focus-visible, .jupyter-widgets .widget-readout:focus-visible," +
    " .jupyter-widgets button:focus-visible, .jupyter-widgets input:focus-visible" +
    " { outline: 2px solid var(--jp-brand-color1, #1565c0); outline-offset: 2px; }";
  var labels = 0;

  function first(bound) {
    return Array.isArray(bound) ? bound[0] : bound;
  }

  function setAll(element, attributes) {
    Object.keys(attributes).forEach(function (key) {
      var value = attributes[key];
      if (value === null) {
        if (element.hasAttribute(key)) element.removeAttribute(key);
      } else if (element.getAttribute(key) !== value) {
        element.setAttribute(key, value);
      }
    });
  }

  // The handle of one slider row: named by its label, its range and value as the readout says.
  function describeSlider(row) {
    var target = row.querySelector(".noUi-target");
    var handle = row.querySelector(".noUi-handle");
    var label = row.querySelector(".widget-label");
    var readout = row.querySelector(".widget-readout");
    if (!target || !handle || !target.noUiSlider) return;
    var name = label ? label.textContent.trim() : "";
    if (name && !label.id) label.id = "ros2-course-label-" + ++labels;
    var range = target.noUiSlider.options.range;
    var shown = readout ? readout.textContent.trim() : "";
    var now = shown !== "" && isFinite(Number(shown)) ? Number(shown) : null;
    if (now === null) now = Number(Number(target.noUiSlider.get()).toFixed(6));
    setAll(handle, {
      "aria-labelledby": name ? label.id : null,
      "aria-valuemin": String(first(range.min)),
      "aria-valuemax": String(first(range.max)),
      "aria-valuenow": String(now),
      "aria-valuetext": shown || String(now),
      "aria-disabled": target.hasAttribute("disabled") ? "true" : null,
      title: label && label.title && label.title !== "null" ? label.title : null,
    });
    // the readout takes a typed value: a text box, named after the slider
    if (readout && name) setAll(readout, { role: "textbox", "aria-label": name + ", typed value" });
  }

  function slidersOf(node) {
    var element = node.nodeType === 1 ? node : node.parentElement;
    if (!element || !element.closest) return [];
    var row = element.closest(SLIDER);
    if (row) return [row];
    return element.querySelectorAll ? Array.prototype.slice.call(element.querySelectorAll(SLIDER)) : [];
  }

  function followSliders() {
    var observer = new MutationObserver(function (mutations) {
      var rows = new Set();
      mutations.forEach(function (mutation) {
        slidersOf(mutation.target).forEach(function (row) { rows.add(row); });
        Array.prototype.forEach.call(mutation.addedNodes, function (node) {
          slidersOf(node).forEach(function (row) { rows.add(row); });
        });
      });
      rows.forEach(describeSlider);
    });
    observer.observe(document.body, {
      subtree: true, childList: true, characterData: true, attributes: true, attributeFilter: WATCHED,
    });
    document.querySelectorAll(SLIDER).forEach(describeSlider);
  }

  // Escape in a widget of a cell's output: that cell becomes the active one, in command mode.
  function escapeLeavesWidgets(app) {
    document.addEventListener("keydown", function (event) {
      var element = event.target;
      if (event.key !== "Escape" || !element.closest || !element.closest(".jupyter-widgets")) {
        return;
      }
      var cell = element.closest(".jp-Cell");
      var panel = app.shell.currentWidget;
      var notebook = panel && panel.content;
      if (!cell || !notebook || !notebook.widgets) return;
      var index = notebook.widgets.findIndex(function (c) { return c.node === cell; });
      if (index < 0) return;
      event.preventDefault();
      event.stopPropagation();
      if (element.blur) element.blur();
      notebook.activeCellIndex = index;
      notebook.deselectAll(); // the active cell alone, as moving to a cell by keyboard leaves it
      notebook.mode = "command";
      notebook.activeCell.node.focus();
    }, true);
  }

  var widgetAccess = {
    id: NAME + ":widget-access",
    description: "Slider handles named by their label, with their true range and rounded value; Escape leaves a widget.",
    autoStart: true,
    activate: function (app) {
      var style = document.createElement("style");
      style.id = "ros2-course-widget-access";
      style.textContent = FOCUS_STYLE;
      document.head.appendChild(style);
      followSliders();
      escapeLeavesWidgets(app);
    },
  };

  window._JUPYTERLAB = window._JUPYTERLAB || {};
  window._JUPYTERLAB[NAME] = {
    init: function () {},
    get: function (module) {
      if (module !== "./extension") {
        return Promise.reject(new Error(NAME + " has no module " + module));
      }
      return Promise.resolve(function () {
        return { __esModule: true, default: [plugin, widgetAccess] };
      });
    },
  };
})();
