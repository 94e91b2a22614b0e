"""The simple tracker with a flaw: it drops every road user that is partly
occluded (a visible fraction below 1), as a detector that needs the whole
outline would. Its scenario fails on recall."""

from osi_sut import serve
from tracker import Tracker

if __name__ == "__main__":
    serve(Tracker(keep=lambda fraction: fraction >= 1.0))
