"""Turtlesim's window: the SVG of a scene and the address a learner opens (pure)."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from course_lib.turtlesim_view import PenLine, Scene, TurtlePose, render_svg, window_url

SVG = "{http://www.w3.org/2000/svg}"


def test_svg_draws_background_then_lines_then_turtles() -> None:
    scene = Scene(
        background=(150, 86, 255),
        lines=(PenLine((179, 184, 255), 3, ((249.5, 249.5), (300.0, 249.5))),),
        turtles=(TurtlePose("turtle1", 300.0, 249.5, 1.5707963),),
    )
    root = ET.fromstring(render_svg(scene))
    assert (root.get("width"), root.get("height")) == ("500", "500")
    title, desc, background, line, turtle = list(root)
    assert root.get("role") == "img" and title.tag == f"{SVG}title"  # its text alternative
    assert desc.text == "turtle1 at x 6.67, y 5.54, theta 1.57 rad; 1 pen line drawn."
    assert background.get("fill") == "rgb(150,86,255)"
    assert line.tag == f"{SVG}polyline" and line.get("stroke") == "rgb(179,184,255)"
    assert line.get("points") == "249.5,249.5 300.0,249.5"
    # a quarter turn counter-clockwise points up: a negative SVG rotation (rows go down)
    assert turtle.get("transform") == "translate(300.00 249.50) rotate(-90.00)"
    assert turtle.get("data-name") == "turtle1"


def test_window_address_goes_through_the_labs_proxy_in_a_lab_terminal() -> None:
    lab = {"JUPYTER_SERVER_URL": "http://127.0.0.1:8888/"}
    assert window_url(40123, lab) == "http://127.0.0.1:8888/proxy/40123/"
    hub = {**lab, "JUPYTERHUB_SERVICE_PREFIX": "/user/ada/"}
    assert window_url(40123, hub) == "/user/ada/proxy/40123/"
    assert window_url(40123, {}) == "http://127.0.0.1:40123/"
    assert window_url(40123, {**lab, "COURSE_VIEWER_URL": "direct"}) == "http://127.0.0.1:40123/"
