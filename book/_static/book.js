// Code, outputs and tables wider than the page scroll sideways: each such block takes the keyboard's
// focus (Tab), so it can be scrolled with the arrow keys (WCAG 2.1.1).
function focusableScrollers() {
  for (const block of document.querySelectorAll("article pre, article .table-wrapper")) {
    const scrolls = block.scrollWidth > block.clientWidth;
    if (scrolls && !block.hasAttribute("tabindex")) {
      block.setAttribute("tabindex", "0");
    } else if (!scrolls && block.getAttribute("tabindex") === "0") {
      block.removeAttribute("tabindex");
    }
  }
}
document.addEventListener("DOMContentLoaded", focusableScrollers);
window.addEventListener("resize", focusableScrollers);
