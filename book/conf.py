"""Sphinx settings of the course's book (`make book`; course_lib/book stages the sources)."""

project = "ROS 2 parameters, interactively"
author = "the course's authors"
copyright = "the course's authors"
extensions = ["myst_nb"]
nb_execution_mode = "off"  # the pages show the outputs stored with the lessons
nb_merge_streams = True
myst_heading_anchors = 3  # `guide.md#a-heading` links, as GitHub makes them
exclude_patterns = ["_build", "README.md"]
html_theme = "furo"
html_title = project
html_static_path = ["_static"]
html_css_files = ["book.css"]
html_js_files = ["book.js"]
html_copy_source = False  # the notebooks are in the repository; the site stays small
html_show_sourcelink = False
html_show_sphinx = False
html_last_updated_fmt = None  # two builds of one commit give the same pages
