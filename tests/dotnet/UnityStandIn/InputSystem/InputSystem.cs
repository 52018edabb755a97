// COMPILE CHECK ONLY. Signature-only stand-in for com.unity.inputsystem 1.x: no behaviour.
using System;
using UnityEngine;

namespace UnityEngine.InputSystem.Controls
{
    public class ButtonControl
    {
        public bool isPressed => throw new NotSupportedException();
    }

    public class Vector2Control
    {
        public Vector2 ReadValue() => throw new NotSupportedException();
    }

    public class TouchControl
    {
        public ButtonControl press => throw new NotSupportedException();
        public Vector2Control position => throw new NotSupportedException();
    }
}

namespace UnityEngine.InputSystem
{
    using UnityEngine.InputSystem.Controls;

    public class Pointer
    {
        public Vector2Control position => throw new NotSupportedException();
    }

    public class Mouse : Pointer
    {
        public static Mouse current => throw new NotSupportedException();
        public ButtonControl leftButton => throw new NotSupportedException();
    }

    public class Touchscreen : Pointer
    {
        public static Touchscreen current => throw new NotSupportedException();
        public TouchControl primaryTouch => throw new NotSupportedException();
    }
}
