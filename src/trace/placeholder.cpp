// placeholder so the stage library exists
