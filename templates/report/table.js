// The spec table: a click on a heading sorts by that column (again: the other way), by
// each cell's data-value where it has one, else by its text; typing in the box keeps the
// rows whose text contains every word typed. Nothing is fetched.
(function () {
  var table = document.getElementById("specs");
  var box = document.getElementById("spec-filter");
  if (!table || !box) { return; }
  var body = table.tBodies[0];
  var heads = table.tHead.rows[0].cells;
  function key(row, i) {
    var c = row.cells[i];
    var v = c.getAttribute("data-value");
    return v !== null ? parseFloat(v) : c.textContent.toLowerCase();
  }
  Array.prototype.forEach.call(heads, function (th, i) {
    th.style.cursor = "pointer";
    th.title = "sort by " + th.textContent;
    th.addEventListener("click", function () {
      var down = table.getAttribute("data-sorted") === String(i) &&
        table.getAttribute("data-order") === "up";
      var rows = Array.prototype.slice.call(body.rows);
      rows.sort(function (a, b) {
        var x = key(a, i), y = key(b, i);
        var c = (typeof x === "number" && typeof y === "number") ? x - y :
          String(x).localeCompare(String(y));
        return down ? -c : c;
      });
      rows.forEach(function (r) { body.appendChild(r); });
      table.setAttribute("data-sorted", String(i));
      table.setAttribute("data-order", down ? "down" : "up");
    });
  });
  box.addEventListener("input", function () {
    var words = box.value.toLowerCase().split(/\s+/).filter(Boolean);
    var shown = 0;
    Array.prototype.forEach.call(body.rows, function (r) {
      var t = r.textContent.toLowerCase();
      var keep = words.every(function (w) { return t.indexOf(w) >= 0; });
      r.style.display = keep ? "" : "none";
      if (keep) { shown++; }
    });
    table.setAttribute("data-shown", String(shown));
  });
})();
