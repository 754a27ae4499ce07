"""The web app's routers: the pages and static files, the catalogue the form is made from, and the tile's answers."""
