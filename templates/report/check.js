// Marks on <body> how many of the page's images loaded and how many did not, once the
// page has loaded: a broken picture shows in the DOM, not only on screen.
window.addEventListener("load", function () {
  var loaded = 0, broken = 0;
  for (var i = 0; i < document.images.length; i++) {
    var img = document.images[i];
    if (img.complete && img.naturalWidth > 0) { loaded++; } else { broken++; }
  }
  document.body.setAttribute("data-images-loaded", String(loaded));
  document.body.setAttribute("data-images-broken", String(broken));
});
